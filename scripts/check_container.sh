#!/usr/bin/env bash
# Build the container image of docker/Dockerfile for real and run tests inside it: the rostest of the C++ talker
# and the Python listener, and the simulator's ROS-free PyODE acceptance tests. Prints a final line
# "N passed, N failed" and exits non-zero on any failure.
#
# Engine: docker when `docker info` answers; else podman when it can run containers here; else buildah (as root,
# chroot isolation: no daemon, no runtime), installed with apt when missing. docker pulls debian:bookworm as usual;
# for podman/buildah a missing debian:bookworm image is made locally with debootstrap from this machine's own
# Debian mirror (read from its apt sources, or $DEBIAN_MIRROR), and the rootfs tarball is cached in $CHECK_CACHE_DIR
# (default /var/cache/turtle_sim_ode as root, else ~/.cache/turtle_sim_ode), so no registry is needed and later runs
# skip debootstrap. Image layers are cached by the engine (--layers): when only sources change, a run rebuilds the
# workspace layer and nothing before it.
#
# Environment: CONTAINER_ENGINE=docker|podman|buildah (skip detection), CHECK_IMAGE (tag, default
# turtle_sim_ode:check), CHECK_CACHE_DIR, DEBIAN_MIRROR.
set -euo pipefail
script="$(cd "$(dirname "$0")" && pwd)/$(basename "$0")"
cd "$(dirname "$script")/.."
export DEBIAN_FRONTEND=noninteractive

image=${CHECK_IMAGE:-turtle_sim_ode:check}
base_image=docker.io/library/debian:bookworm
start=$(date +%s)
phase_start=$start

log() { echo "check_container: $*"; }
phase_done() {
  local now
  now=$(date +%s)
  log "$1 took $((now - phase_start)) s"
  phase_start=$now
}

# --- engine -------------------------------------------------------------------------------------------------------
as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

apt_install_missing() {  # apt_install_missing COMMAND PACKAGE ...: install the packages unless COMMAND exists
  local command=$1
  shift
  command -v "$command" > /dev/null && return 0
  log "installing $* with apt"
  as_root apt-get -o DPkg::Lock::Timeout=600 update -q
  as_root apt-get -o DPkg::Lock::Timeout=600 install -y -q --no-install-recommends "$@"
}

engine=${CONTAINER_ENGINE:-}
if [ -z "$engine" ]; then
  if command -v docker > /dev/null && docker info > /dev/null 2>&1; then
    engine=docker
  elif command -v podman > /dev/null && podman info > /dev/null 2>&1; then
    engine=podman  # confirmed below, once the base image exists, by running a container
  else
    engine=buildah
  fi
fi
case "$engine" in docker | podman | buildah) ;; *) echo "CONTAINER_ENGINE: docker, podman or buildah" >&2; exit 2 ;; esac

if [ "$engine" = buildah ] && [ "$(id -u)" -ne 0 ]; then
  log "buildah runs as root here (chroot isolation): re-running with sudo"
  exec sudo --preserve-env=CONTAINER_ENGINE,CHECK_IMAGE,CHECK_CACHE_DIR,DEBIAN_MIRROR "$script" "$@"
fi

# --- base image (podman, buildah): debootstrap, cached --------------------------------------------------------------
if [ "$(id -u)" -eq 0 ]; then cache_dir=${CHECK_CACHE_DIR:-/var/cache/turtle_sim_ode}; else
  cache_dir=${CHECK_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/turtle_sim_ode}; fi
arch=$(dpkg --print-architecture 2> /dev/null || uname -m)
rootfs_tarball="$cache_dir/debian-bookworm-minbase-$arch.tar"
work_dir=""
container=""
results=""

unmount_below() {  # debootstrap may leave /proc or /sys mounted in its target: unmount them before removing it
  local mount
  for mount in $(findmnt -rn -o TARGET | grep "^$1/" | sort -r); do as_root umount -l "$mount" || true; done
}

cleanup() {
  if [ -n "$container" ]; then buildah rm "$container" > /dev/null 2>&1 || true; fi
  if [ -n "$work_dir" ] && [ -d "$work_dir" ]; then
    unmount_below "$work_dir"
    as_root rm -rf --one-file-system "$work_dir"
  fi
  if [ -n "$results" ]; then rm -rf "$results" 2> /dev/null || true; fi
}
trap cleanup EXIT

host_apt_entries() {  # "URI SUITE" of every enabled deb entry in this machine's apt sources (both formats)
  local file
  for file in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$file" ] || continue
    awk '$1 == "deb" { i = 2; if ($i ~ /^\[/) { while (i < NF && $i !~ /\]$/) i++; i++ } print $i, $(i + 1) }' "$file"
  done
  for file in /etc/apt/sources.list.d/*.sources; do
    [ -f "$file" ] || continue
    awk 'function flush() { if (types ~ /(^| )deb( |$)/ && enabled !~ /^[Nn]o/) {
                              n = split(uris, u, " "); m = split(suites, s, " ")
                              for (i = 1; i <= n; i++) for (j = 1; j <= m; j++) print u[i], s[j] }
                            types = uris = suites = enabled = "" }
         /^[ \t]*$/ { flush(); next }
         /^#/ { next }
         tolower($1) == "types:" { $1 = ""; types = $0 }
         tolower($1) == "uris:" { $1 = ""; uris = $0 }
         tolower($1) == "suites:" { $1 = ""; suites = $0 }
         tolower($1) == "enabled:" { enabled = $2 }
         END { flush() }' "$file"
  done
}

make_rootfs_tarball() {
  local codenames='bookworm|trixie|bullseye|forky|sid|stable|testing|unstable|oldstable'
  local mirror security
  mirror=${DEBIAN_MIRROR:-$(host_apt_entries | awk -v re="^($codenames)$" '$2 ~ re { print $1; exit }')}
  security=$(host_apt_entries | awk -v re="^($codenames)-security$" '$2 ~ re { print $1; exit }')
  if [ -z "$mirror" ]; then
    echo "check_container: no Debian mirror in this machine's apt sources: set DEBIAN_MIRROR=<Debian mirror URL>" >&2
    exit 1
  fi
  apt_install_missing debootstrap debootstrap
  log "debootstrap --variant=minbase bookworm from $mirror"
  mkdir -p "$cache_dir"
  work_dir=$(mktemp -d /var/tmp/check_container.XXXXXX)
  as_root debootstrap --variant=minbase bookworm "$work_dir/rootfs" "$mirror"
  # The image's apt sources: the same mirror as this machine, with bookworm-updates and (when this machine has one)
  # the security archive, like the debian:bookworm image of a registry.
  {
    echo "deb $mirror bookworm main"
    echo "deb $mirror bookworm-updates main"
    if [ -n "$security" ]; then echo "deb $security bookworm-security main"; fi
  } | as_root tee "$work_dir/rootfs/etc/apt/sources.list" > /dev/null
  as_root find "$work_dir/rootfs/var/cache/apt/archives" "$work_dir/rootfs/var/lib/apt/lists" -maxdepth 1 -type f \
    -delete
  unmount_below "$work_dir"
  as_root tar --numeric-owner -C "$work_dir/rootfs" -cf "$rootfs_tarball.tmp" .
  as_root chown "$(id -u):$(id -g)" "$rootfs_tarball.tmp"
  mv "$rootfs_tarball.tmp" "$rootfs_tarball"
  unmount_below "$work_dir"
  as_root rm -rf --one-file-system "$work_dir"
  work_dir=""
}

ensure_base_image() {  # ensure_base_image podman|buildah
  local tool=$1 ctr
  if { [ "$tool" = podman ] && podman image exists "$base_image"; } \
     || { [ "$tool" = buildah ] && buildah inspect --type image "$base_image" > /dev/null 2>&1; }; then
    log "$tool: base image $base_image present"
    return 0
  fi
  [ -s "$rootfs_tarball" ] || make_rootfs_tarball
  log "$tool: importing $rootfs_tarball as $base_image"
  local path=PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
  if [ "$tool" = podman ]; then
    podman import --change "ENV $path" --change 'CMD ["bash"]' "$rootfs_tarball" "$base_image" > /dev/null
  else
    ctr=$(buildah from scratch)
    buildah add "$ctr" "$rootfs_tarball" / > /dev/null
    buildah config --env "$path" --cmd bash "$ctr"
    buildah commit --rm "$ctr" "$base_image" > /dev/null
  fi
}

if [ "$engine" = podman ]; then
  ensure_base_image podman
  if [ -z "${CONTAINER_ENGINE:-}" ] && ! podman run --rm --pull=never --network none "$base_image" true > /dev/null 2>&1; then
    log "podman cannot run containers here: using buildah"
    engine=buildah
    if [ "$(id -u)" -ne 0 ]; then
      exec sudo --preserve-env=CHECK_IMAGE,CHECK_CACHE_DIR,DEBIAN_MIRROR env CONTAINER_ENGINE=buildah "$script" "$@"
    fi
  fi
fi
if [ "$engine" = buildah ]; then
  apt_install_missing buildah buildah
  ensure_base_image buildah
fi
log "engine $engine"
phase_done "base image"

# --- build ----------------------------------------------------------------------------------------------------------
image_id() {
  case "$engine" in
    buildah) buildah inspect --type image --format '{{.FromImageID}}' "$1" 2> /dev/null || true ;;
    *) "$engine" image inspect --format '{{.Id}}' "$1" 2> /dev/null || true ;;
  esac
}
previous_image=$(image_id "$image")

# A machine behind a TLS-inspecting proxy trusts that proxy's CA (/usr/local/share/ca-certificates); the image must
# too, or pip cannot reach PyPI in it (install_deps.sh installs xacro from there). The base image gets this machine's
# extra CA certificates, its CA bundle and a pip.conf naming that bundle, as a layer tagged by their hash, so the
# engine's layer cache survives repeated runs. Machines without extra CAs build on debian:bookworm itself.
build_base=debian:bookworm
extra_cas=(/usr/local/share/ca-certificates/*.crt)
if [ -e "${extra_cas[0]}" ]; then
  digest=$(cat "${extra_cas[@]}" /etc/ssl/certs/ca-certificates.crt | sha256sum | cut -c1-12)
  trusted_base=localhost/turtle_sim_ode-base:bookworm-$digest
  if [ -z "$(image_id "$trusted_base")" ]; then
    trust_dir=$(mktemp -d /tmp/check_container_trust.XXXXXX)
    mkdir "$trust_dir/ca"
    cp "${extra_cas[@]}" "$trust_dir/ca/"
    cp /etc/ssl/certs/ca-certificates.crt "$trust_dir/host-ca-certificates.crt"
    printf '[global]\ncert = /etc/ssl/host-ca-certificates.crt\n' > "$trust_dir/pip.conf"
    printf 'FROM %s\nCOPY ca/ /usr/local/share/ca-certificates/\nCOPY host-ca-certificates.crt /etc/ssl/\nCOPY pip.conf /etc/pip.conf\n' \
      "$base_image" > "$trust_dir/Containerfile"
    case "$engine" in
      docker) docker build -f "$trust_dir/Containerfile" -t "$trusted_base" "$trust_dir" ;;
      podman) podman build --format docker --pull=never -f "$trust_dir/Containerfile" -t "$trusted_base" "$trust_dir" ;;
      buildah)
        buildah bud --format docker --isolation chroot --pull=never -f "$trust_dir/Containerfile" -t "$trusted_base" \
          "$trust_dir"
        ;;
    esac
    rm -rf "$trust_dir"
  fi
  build_base=$trusted_base
  log "base image with this machine's CA certificates: $trusted_base"
fi
build_args=(-f docker/Dockerfile -t "$image" --build-arg BASE="$build_base")
case "$engine" in
  docker) docker build "${build_args[@]}" . ;;
  podman) podman build --format docker --layers --force-rm --pull=never "${build_args[@]}" . ;;
  buildah) buildah bud --format docker --isolation chroot --layers --force-rm --pull=never "${build_args[@]}" . ;;
esac
# The image of the previous run, now untagged: removing it frees the layers only it used (its cached parents that
# the new image shares stay), so that repeated runs do not fill the disk.
if [ -n "$previous_image" ] && [ "$previous_image" != "$(image_id "$image")" ]; then
  "$engine" rmi "$previous_image" > /dev/null 2>&1 || true
fi
phase_done "image build"

# --- tests inside the image -----------------------------------------------------------------------------------------
results=$(mktemp -d /tmp/check_container_results.XXXXXX)
chmod 0777 "$results"

# Runs in the image, in /workspace, after the entrypoint's ROS setup. Results go to /results as JUnit XML.
read -r -d '' inner_script << 'EOF' || true
set -u
cd /workspace || exit 1
export HOME=${HOME:-$(getent passwd "$(id -u)" | cut -d: -f6)}
status=0
mkdir -p /results/rostest /results/pytest

echo "== rostest: C++ talker, Python listener"
ROS_TEST_RESULTS_DIR=/results/rostest timeout 300 \
  rostest beginner_tutorials talker_listener.test talker_lang:=cpp listener_lang:=python || status=1

echo "== simulator smoke test (ROS-free PyODE)"
sim=catkin_ws/src/turtle_sim_ode/test/unit
if compgen -G "$sim/test_*acceptance*.py" > /dev/null; then
  sim_args=("$sim" -k acceptance)
elif compgen -G "$sim/test_*.py" > /dev/null; then
  sim_args=("$sim")
else
  # No simulator suite yet: PyODE itself must integrate a free fall.
  mkdir -p /tmp/pyode_smoke
  cat > /tmp/pyode_smoke/test_pyode_smoke.py << 'PY'
import ode


def test_free_fall():
    world = ode.World()
    world.setGravity((0, 0, -9.81))
    body = ode.Body(world)
    mass = ode.Mass()
    mass.setSphere(1000, 0.1)
    body.setMass(mass)
    for _ in range(1000):
        world.step(0.001)
    assert abs(body.getPosition()[2] + 0.5 * 9.81) < 0.05
PY
  sim_args=(/tmp/pyode_smoke)
fi
timeout 600 /usr/bin/python3 -m pytest -q -p no:cacheprovider "${sim_args[@]}" \
  --junitxml=/results/pytest/turtle_sim_ode.xml || status=1
exit "$status"
EOF

inner_status=0
case "$engine" in
  docker | podman)
    "$engine" run --rm --network none --security-opt label=disable -v "$results:/results" "$image" \
      bash -c "$inner_script" || inner_status=$?
    ;;
  buildah)
    container=$(buildah from --pull=never "$image")
    buildah run --isolation chroot -v "$results:/results" "$container" -- \
      /usr/local/bin/entrypoint.sh bash -c "$inner_script" || inner_status=$?
    ;;
esac
phase_done "tests in the image"

# --- summary --------------------------------------------------------------------------------------------------------
summary=$(/usr/bin/python3 scripts/lib/summarize_results.py "$results" || true)
echo "$summary" | grep '^FAILED' || true
read -r passed failed < <(echo "$summary" | tail -1 | awk '{ print $1, $3 }')
passed=${passed:-0}
failed=${failed:-0}
if [ "$inner_status" -ne 0 ] && [ "$failed" -eq 0 ]; then
  log "a test command failed (exit $inner_status) without a failing result"
  failed=1
fi
log "total $(($(date +%s) - start)) s"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
