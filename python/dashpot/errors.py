"""The exceptions the client raises.

dashpotd reports every failure as an RFC 9457 problem document: a 4xx/5xx answer of type
application/problem+json before the first byte, or an ``{"type": "error", ...}`` line that ends a stream which
had already answered 200. Both become one exception, :class:`ProblemError`, so a caller needs one ``except``
whichever way the run failed. Transport failures (refused connections, timeouts) stay the exceptions of
``requests`` (``requests.exceptions.ConnectionError``, ``requests.exceptions.Timeout``).
"""

from collections import namedtuple

#: One located error of a request body: ``pointer`` is the JSON Pointer (RFC 6901) of the member it is
#: about ("" for the whole document), ``detail`` what is wrong with it.
FieldError = namedtuple("FieldError", ["pointer", "detail"])


class DashpotError(Exception):
    """Base class of every error this package raises itself."""


class ProblemError(DashpotError):
    """The daemon said no: a problem document, or an error line inside a stream.

    Attributes: ``status`` (HTTP status, or the status of the stream's error line), ``title``, ``detail``,
    ``type`` (the problem type URI, e.g. ``/problems/invalid-spec``; None for a stream's error line),
    ``errors`` (a list of :data:`FieldError`, each with its JSON Pointer; empty when the daemon named no
    member), ``in_stream`` (True when the answer had started with 200 and the failure came later) and
    ``document`` (the parsed JSON as sent, or None).
    """

    def __init__(self, status, title, detail, errors=(), type=None, in_stream=False, document=None):
        self.status = status
        self.title = title
        self.detail = detail
        self.errors = [e if isinstance(e, FieldError) else FieldError(e.get("pointer", ""), e.get("detail", ""))
                       for e in errors]
        self.type = type
        self.in_stream = in_stream
        self.document = document
        super().__init__(self._message())

    @property
    def pointers(self):
        """The JSON Pointers of the located errors, in the daemon's order."""
        return [e.pointer for e in self.errors]

    def _message(self):
        where = "in the stream" if self.in_stream else "HTTP"
        text = "%s %s: %s" % (where, self.status, self.title)
        if self.detail and self.detail != self.title:
            text += " (%s)" % self.detail
        for e in self.errors:
            text += "\n  %s: %s" % (e.pointer or "(document)", e.detail)
        return text

    @classmethod
    def from_document(cls, status, document, in_stream=False):
        """Builds the exception from a parsed problem document or stream error object."""
        if not isinstance(document, dict):
            return cls(status, "HTTP %s" % status, str(document), in_stream=in_stream)
        return cls(document.get("status", status), document.get("title", ""), document.get("detail", ""),
                   document.get("errors", ()), document.get("type"), in_stream, document)


class StreamError(DashpotError):
    """A stream ended without its summary line and without an error line: the connection was cut."""


class DaemonError(DashpotError):
    """The local dashpotd could not be found or did not start; the message carries its log."""
