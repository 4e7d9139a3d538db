#!/usr/bin/env bash
# scripts/image.sh - `make image`: builds the Dockerfile into dashpot:VERSION with docker (when its daemon
# answers) or podman (installed from Debian when neither works, as root), and works where no registry is
# reachable: a base image the Dockerfile names (debian:12, debian:12-slim) that is neither present nor
# pullable is made here, as a Debian 12 root filesystem from `debootstrap --variant=minbase bookworm` off the
# Debian mirror this machine's apt already uses, imported under that name. The rootfs is cached in
# $DASHPOT_IMAGE_CACHE (default /var/cache/dashpot-image) for the next run; a missing, stale, corrupt or
# unwritable cache only costs the debootstrap again. Writes $BUILD/image.env (ENGINE, IMAGE, BUILD_ISOLATION)
# for tests/test_image.sh. docs/operations.md, "Container image", explains it.
#
# Environment: DASHPOT_IMAGE_ENGINE=docker|podman forces the engine; DASHPOT_IMAGE_BASE=auto (present, else
# pull, else debootstrap), pull or debootstrap; DASHPOT_DEBIAN_MIRROR overrides the mirror.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
CACHE=${DASHPOT_IMAGE_CACHE-/var/cache/dashpot-image}
BASE_MODE=${DASHPOT_IMAGE_BASE:-auto}
version=$(sed -n 's/^#define DP_VERSION "\(.*\)"$/\1/p' include/dashpot/json.h)
IMAGE=dashpot:${version:?no DP_VERSION in include/dashpot/json.h}
say() { echo "image: $*" >&2; }
die() { say "$*"; exit 1; }

# ---- the engine ----------------------------------------------------------------------------------------------
# A docker client without a daemon (common in sandboxes and CI images) does not count as installed.
pick_engine() {
    case ${DASHPOT_IMAGE_ENGINE:-} in docker | podman) echo "$DASHPOT_IMAGE_ENGINE"; return ;; esac
    if command -v docker >/dev/null && timeout 20 docker info >/dev/null 2>&1; then echo docker; return; fi
    command -v podman >/dev/null || bash scripts/install-deps.sh --image >&2 || exit 1
    echo podman
}
ENGINE=$(pick_engine)
[ "$ENGINE" = podman ] && { bash scripts/install-deps.sh --image >&2 || exit 1; }
has_image() { "$ENGINE" image inspect "$1" >/dev/null 2>&1; }

# ---- the Debian mirror ---------------------------------------------------------------------------------------
# The first URI apt uses for suite $1 (one-line .list files and deb822 .sources files), else deb.debian.org.
apt_uri() {
    local suite=$1 f u
    for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
        [ -r "$f" ] || continue
        u=$(sed -E 's/#.*//; s/\[[^]]*\]//' "$f" | awk -v s="$suite" '$1 == "deb" && $3 == s { print $2; exit }')
        [ -n "$u" ] && { echo "$u"; return 0; }
    done
    for f in /etc/apt/sources.list.d/*.sources; do
        [ -r "$f" ] || continue
        u=$(awk -v s="$suite" -v RS= '{ uri = ""; ok = 0; n = split($0, l, "\n")
            for (j = 1; j <= n; j++) { if (l[j] ~ /^#/) continue
                if (l[j] ~ /^Types:/ && l[j] !~ /[ \t]deb([ \t]|$)/) next
                if (l[j] ~ /^URIs:/) { split(l[j], w, " "); uri = w[2] }
                if (l[j] ~ /^Suites:/) { m = split(l[j], w, " "); for (k = 2; k <= m; k++) if (w[k] == s) ok = 1 } }
            if (ok && uri != "") { print uri; exit } }' "$f")
        [ -n "$u" ] && { echo "$u"; return 0; }
    done
    return 1
}
MIRROR=${DASHPOT_DEBIAN_MIRROR:-$(apt_uri bookworm || echo http://deb.debian.org/debian)}
SECURITY=$(apt_uri bookworm-security || true)

# ---- a base made with debootstrap ----------------------------------------------------------------------------
WORK=$(mktemp -d /var/tmp/dashpot-image.XXXXXX)
trap 'rm -rf "$WORK"' EXIT

# The rootfs as a tar file in $WORK/rootfs.tar: from the cache when it is younger than 30 days and reads back,
# else from debootstrap (then cached, atomically, if the cache is writable).
rootfs_tar() {
    local key cached
    key=$(printf '%s %s' "$MIRROR" "$SECURITY" | md5sum | cut -c1-8)
    cached=$CACHE/bookworm-minbase-$(dpkg --print-architecture)-$key.tar
    if [ -n "$CACHE" ] && [ -n "$(find "$cached" -mtime -30 2>/dev/null)" ] && tar -tf "$cached" >/dev/null 2>&1; then
        say "base rootfs from the cache $cached"
        cp "$cached" "$WORK/rootfs.tar"
        return
    fi
    [ "$(id -u)" -eq 0 ] || die "no $1 image and no registry: making one with debootstrap needs root"
    command -v debootstrap >/dev/null || bash scripts/install-deps.sh --image >&2 || exit 1
    say "debootstrap --variant=minbase bookworm from $MIRROR (about 30 s)"
    local root=$WORK/rootfs
    debootstrap --variant=minbase bookworm "$root" "$MIRROR" > "$WORK/debootstrap.log" 2>&1 ||
        { tail -20 "$WORK/debootstrap.log" >&2; die "debootstrap failed (log above)"; }
    finish_rootfs "$root"
    tar --numeric-owner -C "$root" -cf "$WORK/rootfs.tar" .
    rm -rf "$root"
    if [ -n "$CACHE" ] && mkdir -p "$CACHE" 2>/dev/null && cp "$WORK/rootfs.tar" "$cached.tmp.$$" 2>/dev/null; then
        mv "$cached.tmp.$$" "$cached" && say "cached the base rootfs as $cached"
    else
        rm -f "$cached.tmp.$$" 2>/dev/null
        say "could not cache the base rootfs in $CACHE (continuing)"
    fi
}

# What the registry's debian:12 has beyond a bare debootstrap (debuerreotype's settings): the release's
# updates and security suites, apt that keeps no package caches or translations, and none of the host's
# identity (resolv.conf, hostname: the engine provides them).
finish_rootfs() {
    local root=$1
    {
        echo "deb $MIRROR bookworm main"
        echo "deb $MIRROR bookworm-updates main"
        [ -z "$SECURITY" ] || echo "deb $SECURITY bookworm-security main"
    } > "$root/etc/apt/sources.list"
    cat > "$root/etc/apt/apt.conf.d/docker-clean" <<'EOF'
DPkg::Post-Invoke { "rm -f /var/cache/apt/archives/*.deb /var/cache/apt/archives/partial/*.deb /var/cache/apt/*.bin || true"; };
APT::Update::Post-Invoke { "rm -f /var/cache/apt/archives/*.deb /var/cache/apt/archives/partial/*.deb /var/cache/apt/*.bin || true"; };
Dir::Cache::pkgcache "";
Dir::Cache::srcpkgcache "";
EOF
    echo 'Acquire::Languages "none";' > "$root/etc/apt/apt.conf.d/docker-no-languages"
    echo 'Apt::AutoRemove::SuggestsImportant "false";' > "$root/etc/apt/apt.conf.d/docker-autoremove-suggests"
    rm -rf "$root"/var/cache/apt/archives/*.deb "$root"/var/cache/apt/*.bin "$root"/var/lib/apt/lists/* \
        "$root"/var/log/* "$root/etc/resolv.conf" "$root/etc/hostname" "$root/etc/machine-id"
    : > "$root/etc/machine-id"
}

# The -slim variant, as the registry's: documentation, manual pages and translations removed, and dpkg told
# not to install them again (copyright files and locale.alias stay).
slim_rootfs() {
    local root=$WORK/slim
    mkdir "$root"
    tar --numeric-owner -C "$root" -xf "$WORK/rootfs.tar"
    cat > "$root/etc/dpkg/dpkg.cfg.d/docker" <<'EOF'
path-exclude /usr/share/doc/*
path-include /usr/share/doc/*/copyright
path-exclude /usr/share/man/*
path-exclude /usr/share/groff/*
path-exclude /usr/share/info/*
path-exclude /usr/share/lintian/*
path-exclude /usr/share/linda/*
path-exclude /usr/share/locale/*
path-include /usr/share/locale/locale.alias
EOF
    find "$root/usr/share/doc" -mindepth 1 -not -name copyright -not -type d -delete
    find "$root/usr/share/doc" -mindepth 1 -type d -empty -delete
    find "$root/usr/share/locale" -mindepth 1 -maxdepth 1 -not -name locale.alias -exec rm -rf {} +
    rm -rf "$root"/usr/share/{man,groff,info,lintian,linda}/*
    tar --numeric-owner -C "$root" -cf "$WORK/slim.tar" .
    rm -rf "$root"
}

# make_base NAME: imports the debootstrapped rootfs (slimmed for a *-slim NAME) as NAME.
make_base() {
    local name=$1 tar
    case $name in
        debian:12 | debian:bookworm | debian:12-slim | debian:bookworm-slim) ;;
        *) die "the Dockerfile needs $name: not present, not pullable, and only debian:12[-slim] can be made here" ;;
    esac
    [ -f "$WORK/rootfs.tar" ] || rootfs_tar "$name"
    tar=$WORK/rootfs.tar
    case $name in *-slim) [ -f "$WORK/slim.tar" ] || slim_rootfs; tar=$WORK/slim.tar ;; esac
    "$ENGINE" import --change 'CMD ["bash"]' \
        --change "LABEL org.opencontainers.image.description=\"debootstrap --variant=minbase bookworm $MIRROR\"" \
        "$tar" "$name" >/dev/null || die "$ENGINE import $name failed"
    say "made $name from debootstrap ($(du -m "$tar" | cut -f1) MB)"
}

# The base images are the FROM lines that do not name an earlier stage.
bases=$(awk 'toupper($1) == "FROM" { if (!($2 in stage)) print $2; if (toupper($3) == "AS") stage[$4] = 1 }' Dockerfile |
        sort -u)
for b in $bases; do
    has_image "$b" && [ "$BASE_MODE" != debootstrap ] && continue
    if [ "$BASE_MODE" != debootstrap ] && timeout 120 "$ENGINE" pull "docker.io/library/$b" >/dev/null 2>&1; then
        say "pulled $b"
        [ "$ENGINE" = podman ] && "$ENGINE" tag "docker.io/library/$b" "$b"
        continue
    fi
    [ "$BASE_MODE" = pull ] && die "could not pull $b"
    make_base "$b"
done

# ---- the build -----------------------------------------------------------------------------------------------
# podman: the docker format keeps HEALTHCHECK (OCI images have none); chroot isolation where this machine cannot
# run an OCI container (e.g. a sandbox that refuses setrlimit or has hybrid cgroups), so RUN works anyway.
iso=
if [ "$ENGINE" = podman ]; then
    iso=oci
    timeout 60 podman run --rm --network none "$(echo "$bases" | head -1)" true >/dev/null 2>&1 || iso=chroot
fi
say "building $IMAGE with $ENGINE${iso:+ (isolation $iso)}"
start=$SECONDS
case $ENGINE in
    podman) podman build --format docker --isolation "$iso" -t "$IMAGE" . ;;
    docker) docker build -t "$IMAGE" . ;;
esac
mkdir -p "$BUILD"
printf 'ENGINE=%s\nIMAGE=%s\nBUILD_ISOLATION=%s\n' "$ENGINE" "$IMAGE" "$iso" > "$BUILD/image.env"
say "built $IMAGE in $((SECONDS - start)) s; run it with: $ENGINE run --rm -p 8080:8080 $IMAGE"
