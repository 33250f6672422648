#!/usr/bin/env bash
# Installs the missing Debian packages of the given groups (default: build verify bench) from
# tools/debian-packages.txt. Idempotent: installs nothing when everything is present.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
groups=("$@")
[ ${#groups[@]} -gt 0 ] || groups=(build verify bench)
missing=()
while read -r group pkg; do
  case "$group" in ''|\#*) continue ;; esac
  for g in "${groups[@]}"; do
    if [ "$g" = "$group" ] && ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$pkg")
    fi
  done
done < "$here/debian-packages.txt"
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all packages present (${groups[*]})" >&2
  exit 0
fi
echo "setup: installing ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done" >&2
