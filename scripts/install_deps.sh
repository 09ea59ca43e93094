#!/usr/bin/env bash
# Install every system package the workspace needs, derived from the packages' package.xml files.
# Supported: Debian 12 (Debian's own ROS packages under /usr) and Ubuntu 20.04 with the ROS apt source
# configured (ros-noetic-* under /opt/ros/noetic). Idempotent: apt runs only when something is missing.
set -euo pipefail
cd "$(dirname "$0")/.."

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

. /etc/os-release
case "${ID}:${VERSION_ID:-}" in
  debian:12) platform=debian ;;
  ubuntu:20.04) platform=ubuntu ;;
  *)
    echo "install_deps: unsupported platform '${PRETTY_NAME:-$ID}'." >&2
    echo "Supported: Debian 12 (bookworm), or Ubuntu 20.04 (focal) with the ROS Noetic apt source." >&2
    exit 1 ;;
esac

apt_updated=0
apt_install() {
  if [ "$apt_updated" -eq 0 ]; then $SUDO apt-get update -q; apt_updated=1; fi
  $SUDO apt-get install -y -q --no-install-recommends "$@"
}

# The resolver needs the system Python with its xml module (python3-minimal lacks it; a minimal image may have
# no Python at all).
if ! /usr/bin/python3 -c 'import xml.etree.ElementTree' 2>/dev/null; then apt_install python3; fi

# Not "< <(...)": a failing resolver must stop the script, not look like an empty list.
resolved=$(/usr/bin/python3 scripts/lib/resolve_deps.py --platform "$platform")
mapfile -t wanted <<< "$resolved"
missing=()
for package in "${wanted[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null || true)
  [ "$status" = "installed" ] || missing+=("$package")
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_deps: all ${#wanted[@]} packages present ($platform)."
else
  echo "install_deps: installing ${#missing[@]} of ${#wanted[@]} packages ($platform): ${missing[*]}"
  if [ "$platform" = ubuntu ] && ! apt-cache policy ros-noetic-catkin | grep -q 'Candidate: [0-9]'; then
    apt_install ca-certificates
    if ! apt-cache policy ros-noetic-catkin | grep -q 'Candidate: [0-9]'; then
      echo "install_deps: ros-noetic-* packages not found: configure the ROS Noetic apt source first" >&2
      echo "(see http://wiki.ros.org/noetic/Installation/Ubuntu, steps 1.2-1.3)." >&2
      exit 1
    fi
  fi
  apt_install "${missing[@]}"
fi

# Drop-ins (README "Using packages written for Gazebo"): where the system has no xacro (Debian 12), the
# workspace's xacro package is used, and it runs PyPI's xacro. That library goes, pinned and hash-checked, into a
# folder of its own, not into the system Python (externally managed on Debian 12); its one dependency, PyYAML,
# comes from apt. pip runs only when a pin is missing there. Offline: PIP_NO_INDEX=1 PIP_FIND_LINKS=<wheel folder>.
PYPI_DIR=/usr/local/lib/ros_dropins/python
/usr/bin/python3 scripts/lib/dropins.py apply > /dev/null
pypi_missing=$(/usr/bin/python3 scripts/lib/dropins.py pypi-missing --target "$PYPI_DIR")
if [ -n "$pypi_missing" ]; then
  while read -r requirements; do
    echo "install_deps: pip install --target $PYPI_DIR -r ${requirements#"$PWD"/}"
    $SUDO env PIP_ROOT_USER_ACTION=ignore /usr/bin/python3 -m pip install -q --no-deps --require-hashes --upgrade \
      --target "$PYPI_DIR" -r "$requirements"
  done <<< "$pypi_missing"
else
  echo "install_deps: PyPI libraries of the drop-ins in use present ($PYPI_DIR)."
fi
