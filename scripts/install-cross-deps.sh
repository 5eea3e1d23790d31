#!/bin/sh
# Installs what scripts/cross-test.sh and scripts/embedded-test.sh need on
# Debian 12: qemu-user and the cross compilers for aarch64 (little endian),
# s390x (big endian) and armhf (the embedded profile's 32-bit ARM), and
# adds the two architectures to dpkg so that cross-test.sh can download the
# target's libraries (it unpacks them into a sysroot of its own rather than
# installing them: see the comment at its top).
# Runs apt-get directly as root, through sudo otherwise.
set -eu
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi
export DEBIAN_FRONTEND=noninteractive
for arch in arm64 s390x; do
    if ! dpkg --print-foreign-architectures | grep -qx "$arch"; then
        $SUDO dpkg --add-architecture "$arch"
    fi
done
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends \
    qemu-user gcc-aarch64-linux-gnu libc6-dev-arm64-cross \
    gcc-s390x-linux-gnu libc6-dev-s390x-cross \
    gcc-arm-linux-gnueabihf libc6-dev-armhf-cross >/dev/null
echo "softrast: cross compilers and qemu-user installed"
