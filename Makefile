# Makefile - builds libdashpot.a, the CLI `dashpot`, the daemon `dashpotd`, and runs the tests.
#
#   make            library, CLI and daemon into build/
#   make test       every test program (tests/test_*.c), then the shell integration tests (tests/*.sh)
#   make test SAN=1 the same under AddressSanitizer + UndefinedBehaviorSanitizer (into build-san/)
#   make run        builds and starts dashpotd on 127.0.0.1:8080
#   make bench      benchmarks with their peers, ratios printed (kept out of `test`)
#   make image      the container image dashpot:VERSION, with docker or podman, offline too (docs/operations.md)
#   make deps       installs the Debian packages this needs (as root); `make run` installs only the run ones

SHELL   := /bin/bash
CC      ?= cc
SAN     ?=
BUILD   ?= $(if $(SAN),build-san,build)
OPT     ?= -O2
CFLAGS  ?= $(OPT) -g
WARN    := -std=c17 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes \
           -Wno-missing-field-initializers
ASAN_UBSAN := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
SANFLAGS := $(if $(SAN),$(ASAN_UBSAN))
CPPFLAGS += -Iinclude -Isrc/core -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -MMD -MP
ALL_CFLAGS = $(WARN) $(CFLAGS) $(SANFLAGS)
LDLIBS_CORE := -lgsl -lgslcblas -lm
# The unit tests alone also link LAPACK: an independent reference for the eigensolvers (test_modes.c).
LDLIBS_TEST := -llapack
LDLIBS_JSON := -lcjson
LDLIBS_HTTP := -lmicrohttpd -lpthread
LDFLAGS += $(SANFLAGS)

CORE_SRC := $(shell find src/core -name '*.c' | sort)
JSON_SRC := $(wildcard src/json/*.c)
HTTP_SRC := $(wildcard src/http/*.c)
CLI_SRC  := $(wildcard src/cli/*.c)
LIB_OBJ  := $(CORE_SRC:%.c=$(BUILD)/%.o) $(JSON_SRC:%.c=$(BUILD)/%.o)
HTTP_OBJ := $(HTTP_SRC:%.c=$(BUILD)/%.o)
CLI_OBJ  := $(CLI_SRC:%.c=$(BUILD)/%.o)
LIB      := $(BUILD)/libdashpot.a
TEST_SRC := $(wildcard tests/test_*.c)
TEST_BIN := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
TEST_SH  := $(filter-out tests/test_image.sh,$(wildcard tests/*.sh))
PROGS    := $(BUILD)/dashpot $(if $(HTTP_SRC),$(BUILD)/dashpotd)

.PHONY: all test unit integration run bench deps deps-ok deps-run clean thesis-figures corpus fuzz bench-peers

all: $(LIB) $(PROGS)

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(ALL_CFLAGS) -c $< -o $@

$(LIB): $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/dashpot: $(CLI_OBJ) $(LIB)
	$(CC) $(LDFLAGS) -o $@ $(CLI_OBJ) $(LIB) $(LDLIBS_JSON) $(LDLIBS_CORE)

$(BUILD)/dashpotd: $(HTTP_OBJ) $(LIB)
	$(CC) $(LDFLAGS) -o $@ $(HTTP_OBJ) $(LIB) $(LDLIBS_HTTP) $(LDLIBS_JSON) $(LDLIBS_CORE)

$(BUILD)/tests/%: tests/%.c $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(ALL_CFLAGS) -Itests $< -o $@ $(LIB) -lcmocka $(LDLIBS_JSON) $(LDLIBS_CORE) $(LDLIBS_TEST)

# Every unit test program runs even if an earlier one fails; the target fails if any did.
unit: $(TEST_BIN)
	@fail=0; for t in $(TEST_BIN); do echo "== $$t"; $$t || fail=1; done; exit $$fail

integration: all
	@fail=0; for t in $(TEST_SH); do echo "== $$t"; BUILD=$(BUILD) bash $$t || fail=1; done; exit $$fail

test: deps-ok
	@$(MAKE) --no-print-directory unit integration
	@echo "all tests passed ($(if $(SAN),ASan+UBSan,plain) build)"

deps deps-ok:
	@bash scripts/install-deps.sh

# `make run` needs neither cmocka nor the test tools: only what builds and runs the daemon.
deps-run:
	@bash scripts/install-deps.sh --run

run: deps-run
	@$(MAKE) --no-print-directory all
	./$(BUILD)/dashpotd

thesis-figures: $(BUILD)/dashpot
	bash scripts/thesis-figures.sh $(BUILD)/dashpot data/thesis

# The README's pictures, docs/images/*.png, redrawn from the CLI (scripts/gallery.sh).
.PHONY: gallery
gallery: $(BUILD)/dashpot
	bash scripts/gallery.sh $(BUILD)/dashpot docs/images

# Re-records the answer corpus of tests/test_corpus.sh (tests/corpus/README.md) from this build: only for an
# intended change of behaviour, described in CHANGELOG.md. `bash tests/corpus/record.sh --inputs` also gathers
# the inputs afresh from the docs, the OpenAPI examples, the tests and the page's presets.
corpus: all
	BUILD=$(BUILD) bash tests/corpus/record.sh

# libFuzzer targets (tests/fuzz/fuzz_*.c) over an instrumented build of the library in build-fuzz/; each runs
# FUZZ_SECONDS from its seed corpus, tests/fuzz/corpus-NAME for fuzz_NAME if there is one, else
# tests/fuzz/corpus (copied, so new finds do not dirty the tree; tests/fuzz/seeds.py writes the seeds), and
# fails on any crash, leak, timeout or sanitizer report. fuzz_http links the daemon (src/http but main.c).
FUZZ_SECONDS ?= 60
FUZZ_FLAGS := -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
FUZZ_SRC := $(wildcard tests/fuzz/fuzz_*.c)
FUZZ_HTTP_OBJ := $(filter-out build-fuzz/src/http/main.o,$(HTTP_SRC:%.c=build-fuzz/%.o))
fuzz:
	@bash scripts/install-deps.sh --fuzz
	@$(MAKE) -s --no-print-directory BUILD=build-fuzz CC=clang OPT=-O1 SANFLAGS="$(FUZZ_FLAGS)" build-fuzz/libdashpot.a \
	  $(FUZZ_HTTP_OBJ)
	@fail=0; for f in $(FUZZ_SRC); do \
	  n=$$(basename $$f .c); t=build-fuzz/$$n; seeds=tests/fuzz/corpus-$${n#fuzz_}; \
	  [ -d $$seeds ] || seeds=tests/fuzz/corpus; \
	  case $$n in fuzz_http*) http="$(FUZZ_HTTP_OBJ) $(LDLIBS_HTTP)";; *) http=;; esac; \
	  clang $(CPPFLAGS) -Isrc/http $(WARN) -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all $$f \
	    $$http build-fuzz/libdashpot.a $(LDLIBS_JSON) $(LDLIBS_CORE) -o $$t || exit 1; \
	  rm -rf $$t.corpus && mkdir -p $$t.corpus && cp $$seeds/* $$t.corpus/; \
	  echo "== $$t for $(FUZZ_SECONDS) s from $$seeds"; \
	  $$t -max_total_time=$(FUZZ_SECONDS) -timeout=10 -rss_limit_mb=2048 -max_len=65536 -artifact_prefix=$$t- \
	      -print_final_stats=1 $$t.corpus 2>&1 | \
	      grep -E 'Done|stat::number_of_executed_units|ERROR|SUMMARY|==[0-9]+==|^fuzz_|Test unit written' ; \
	  [ $${PIPESTATUS[0]} -eq 0 ] || fail=1; \
	done; exit $$fail

# The robustness suite, kept out of `make test` for its length (~3 min; CI runs it once, on the plain
# build): the HTTP tests with every daemon under valgrind memcheck (zero definite or indirect leaks, no memory
# error; the 10^7-sample stream skipped), 30 s of mixed load with 64 connections (wrk), the faults
# (1000 hang-ups, slowloris, hostile bodies, divergence, SIGTERM under load), and the container image built
# and run (tests/test_image.sh: about a minute cold, seconds warm; it needs root or a working engine, and the
# network for the Dockerfile's apt-get). Each runs even if one failed.
.PHONY: robustness
robustness: all
	@bash scripts/install-deps.sh --robustness
	@fail=0; echo "== DASHPOT_VALGRIND=1 tests/test_http.sh"; \
	DASHPOT_VALGRIND=1 BUILD=$(BUILD) bash tests/test_http.sh || fail=1; \
	for t in tests/robustness/*.sh tests/test_image.sh; do echo "== $$t"; BUILD=$(BUILD) bash $$t || fail=1; done; \
	exit $$fail

bench: all
	@bash bench/run.sh $(BUILD)

# dashpot's stick-slip solver next to Siconos (installed from Debian if missing): accuracy and speed, for one
# mass (siconos.sh), for networks (network.sh: chains, Burridge-Knopoff scaling, one node vs one mass) and for
# contacts (contact.sh: the bouncing ball, two masses, 100 blocks on stops).
bench-peers: all
	@fail=0; for b in bench/siconos.sh bench/network.sh bench/contact.sh; do echo "== $$b"; BUILD=$(BUILD) bash $$b || fail=1; done; \
	exit $$fail

clean:
	rm -rf build build-san build-fuzz

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)

# ---- make install / make uninstall --------------------------------------------------------------------------
# make install [PREFIX=/usr/local] [DESTDIR=/staging]: dashpotd and dashpot into $(bindir), libdashpot.a into
# $(libdir), the public headers into $(includedir)/dashpot, dashpot.pc (from dashpot.pc.in; it names the final
# PREFIX, its directories relative to ${prefix}; a staged copy is used with PKG_CONFIG_SYSROOT_DIR=$(DESTDIR))
# into $(pkgconfigdir), api/openapi.yaml into $(datadir)/dashpot and the browser page's files (web/) into
# $(datadir)/dashpot/web. The daemon finds those two by itself as <its bin directory>/../share/dashpot
# (no compiled-in PREFIX; with a datadir outside $(PREFIX)/share, point DASHPOT_OPENAPI and DASHPOT_WEB_DIR
# at them: docs/operations.md). `make uninstall` with the same variables removes what `make install` put there.
PREFIX       ?= /usr/local
DESTDIR      ?=
bindir       ?= $(PREFIX)/bin
libdir       ?= $(PREFIX)/lib
includedir   ?= $(PREFIX)/include
datadir      ?= $(PREFIX)/share
pkgconfigdir ?= $(libdir)/pkgconfig
INSTALL      ?= install
INSTALL_HEADERS := $(wildcard include/dashpot/*.h)
INSTALL_OPENAPI := $(wildcard api/openapi.yaml)
INSTALL_WEB     := $(shell find web -maxdepth 1 -type f ! -name '.*' 2>/dev/null)
DP_VERSION_STRING = $(shell sed -n 's/^#define DP_VERSION "\(.*\)"$$/\1/p' include/dashpot/json.h)

install: all
	$(INSTALL) -d $(DESTDIR)$(bindir) $(DESTDIR)$(libdir) $(DESTDIR)$(includedir)/dashpot \
	    $(DESTDIR)$(pkgconfigdir) $(DESTDIR)$(datadir)/dashpot/web
	$(INSTALL) -m 755 $(PROGS) $(DESTDIR)$(bindir)/
	$(INSTALL) -m 644 $(LIB) $(DESTDIR)$(libdir)/
	$(INSTALL) -m 644 $(INSTALL_HEADERS) $(DESTDIR)$(includedir)/dashpot/
	sed -e 's|@prefix@|$(PREFIX)|g' -e 's|@version@|$(DP_VERSION_STRING)|g' \
	    -e 's|@libdir@|$(patsubst $(PREFIX)/%,$${prefix}/%,$(libdir))|g' \
	    -e 's|@includedir@|$(patsubst $(PREFIX)/%,$${prefix}/%,$(includedir))|g' dashpot.pc.in > $(BUILD)/dashpot.pc
	$(INSTALL) -m 644 $(BUILD)/dashpot.pc $(DESTDIR)$(pkgconfigdir)/dashpot.pc
	$(if $(INSTALL_OPENAPI),$(INSTALL) -m 644 $(INSTALL_OPENAPI) $(DESTDIR)$(datadir)/dashpot/)
	$(if $(INSTALL_WEB),$(INSTALL) -m 644 $(INSTALL_WEB) $(DESTDIR)$(datadir)/dashpot/web/)

uninstall:
	rm -f $(addprefix $(DESTDIR)$(bindir)/,$(notdir $(PROGS))) $(DESTDIR)$(libdir)/$(notdir $(LIB)) \
	    $(addprefix $(DESTDIR)$(includedir)/dashpot/,$(notdir $(INSTALL_HEADERS))) \
	    $(DESTDIR)$(pkgconfigdir)/dashpot.pc $(DESTDIR)$(datadir)/dashpot/openapi.yaml \
	    $(addprefix $(DESTDIR)$(datadir)/dashpot/web/,$(notdir $(INSTALL_WEB)))
	-rmdir $(DESTDIR)$(includedir)/dashpot $(DESTDIR)$(datadir)/dashpot/web $(DESTDIR)$(datadir)/dashpot 2>/dev/null

.PHONY: install uninstall

# ---- make image ------------------------------------------------------------------------------------------------
# The Dockerfile built into dashpot:VERSION with docker or podman; where no registry is reachable its Debian
# base is made with debootstrap from the machine's Debian mirror (scripts/image.sh; docs/operations.md,
# "Container image"). tests/test_image.sh builds and runs it (in `make robustness`).
image:
	@BUILD=$(BUILD) bash scripts/image.sh

.PHONY: image
