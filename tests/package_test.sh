#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# The Debian packages as a user gets them: cpack makes them from a build folder, lintian finds
# no errors or warnings in them (where it is installed), their copyright files are
# machine-readable, dpkg installs them into a scratch root (the machine's own packages
# untouched), and the installed lic3d renders a picture on lavapipe. Checks what is installed
# (programs, man pages, completion, desktop entry, icon, documentation, the ParaView plugin and
# Python module where they were built) and what is not (headers, static libraries, also from a
# plain `cmake --install`). ctest runs it as package.deb:
#   sh tests/package_test.sh CMAKE CPACK BUILD_DIR LAVAPIPE_ICD static|shared
# the last saying whether the build links zlib and libpng statically
# (LIC3D_STATIC_SYSTEM_LIBRARIES).
set -eu

cmake=$1
cpack=$2
build=$3
icd=$4
system_libraries=$5
work=$(mktemp -d "${TMPDIR:-/tmp}/lic3d-package.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' INT TERM
fail() {
  echo "package.deb: $*" >&2
  exit 1
}

# The packages, as `cpack -G DEB` in the build folder makes them.
if ! "$cpack" -G DEB --config "$build/CPackConfig.cmake" -B "$work/packages" \
  >"$work/cpack.log" 2>&1; then
  cat "$work/cpack.log" >&2
  fail "cpack failed"
fi
main=$(find "$work/packages" -maxdepth 1 -name 'lic3d_*.deb')
[ -n "$main" ] || fail "no lic3d_*.deb in: $(ls "$work/packages")"
for deb in "$work"/packages/*.deb; do
  echo "package.deb: $(basename "$deb"), $(wc -c <"$deb") bytes"
done

# lintian, Debian's checker of packages against its policy, where it is installed
# (cmake/install-deps.sh installs it): no errors and no warnings. README.md, "Install", lists the
# informational tags that remain.
# A build that links zlib and libpng statically makes packages that carry them, which lintian
# rejects (embedded-library): that tag is left out there, and the test says so.
if command -v lintian >/dev/null; then
  suppress=""
  if [ "$system_libraries" = static ]; then
    suppress="--suppress-tags embedded-library"
    echo "package.deb: lintian's embedded-library left out: this build links zlib and" \
      "libpng statically (LIC3D_STATIC_SYSTEM_LIBRARIES=ON); packages for others come from" \
      "the package preset"
  fi
  # shellcheck disable=SC2086
  if ! lintian --fail-on error,warning $suppress "$work"/packages/*.deb >"$work/lintian.log" 2>&1
  then
    cat "$work/lintian.log" >&2
    fail "lintian found errors or warnings"
  fi
  echo "package.deb: lintian: no errors or warnings ($(lintian --version))"
else
  echo "package.deb: lintian is not installed, the packages are NOT checked with it" \
    "(cmake/install-deps.sh installs it)"
fi

# A scratch root with an empty dpkg database. Its dependencies (libc, Vulkan...) are the
# machine's, so dpkg is told not to look for them there.
root=$work/root
mkdir -p "$root/var/lib/dpkg/info" "$root/var/lib/dpkg/updates"
: >"$root/var/lib/dpkg/status"
: >"$root/var/lib/dpkg/available"
dpkg --root="$root" --log="$work/dpkg.log" --force-not-root --force-depends \
  -i "$work"/packages/*.deb >"$work/dpkg.out" 2>&1 || {
  cat "$work/dpkg.out" >&2
  fail "dpkg -i failed"
}
status=$(dpkg-query --admindir="$root/var/lib/dpkg" -W -f='${Status}' lic3d)
[ "$status" = "install ok installed" ] || fail "dpkg says lic3d is '$status'"

usr=$root/usr
expect() {
  [ -e "$usr/$1" ] || fail "not installed: /usr/$1"
}
expect bin/lic3d
expect share/doc/lic3d/README.md

# Each package's copyright file is machine-readable (DEP-5), which lintian checks in source
# packages only: the Format line first, a "Files: *" paragraph, Copyright and License in every
# Files paragraph, and the text of every licence they name, in the paragraph or in a License
# paragraph of its own. Each also has Debian's changelog.
dep5() {
  awk '
    function fault(why) { printf "%s:%d: %s\n", FILENAME, FNR, why; bad = 1 }
    function paragraph(  n, names, i) {
      if ("Files" in f) {
        if (f["Files"] == "*") all = 1
        if (!("Copyright" in f) || !("License" in f))
          fault("Files paragraph without Copyright or License")
        n = split(f["License"], names, / (and|or) /)
        for (i = 1; i <= n; i++) if (!text) named[names[i]] = FNR; else defined[names[i]] = 1
      } else if ("License" in f) {
        if (!text) fault("License paragraph without the licence text")
        defined[f["License"]] = 1
      } else if (paragraphs > 0 && length(f) > 0) {
        fault("a paragraph with neither Files nor License")
      }
      if (length(f) > 0) paragraphs++
      delete f; field = ""; text = 0
    }
    FNR == 1 && $0 != "Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/" {
      fault("the first line is not the Format line")
    }
    /^$/ { paragraph(); next }
    /^[ \t]/ {
      if (field == "") fault("a continuation line outside a field")
      if (field == "License") text = 1
      next
    }
    /^[A-Za-z][A-Za-z-]*:/ {
      field = substr($0, 1, index($0, ":") - 1)
      value = substr($0, index($0, ":") + 1)
      sub(/^[ \t]+/, "", value); sub(/[ \t]+$/, "", value)
      f[field] = value
      next
    }
    { fault("neither a field nor a continuation line") }
    END {
      paragraph()
      if (!all) fault("no \"Files: *\" paragraph")
      for (name in named) if (!(name in defined)) fault("no text of the licence " name)
      exit bad
    }' "$1"
}
for deb in "$work"/packages/*.deb; do
  package=$(dpkg-deb -f "$deb" Package)
  expect "share/doc/$package/changelog.gz"
  expect "share/doc/$package/copyright"
  dep5 "$usr/share/doc/$package/copyright" >&2 ||
    fail "/usr/share/doc/$package/copyright is not machine-readable (DEP-5)"
done
expect share/bash-completion/completions/lic3d
if [ -x "$build/lic3d-view" ]; then
  expect bin/lic3d-view
  expect share/bash-completion/completions/lic3d-view
  expect share/applications/lic3d-view.desktop
  expect share/icons/hicolor/256x256/apps/lic3d.png
  if command -v desktop-file-validate >/dev/null; then
    desktop-file-validate "$usr/share/applications/lic3d-view.desktop" ||
      fail "desktop-file-validate: lic3d-view.desktop"
  fi
fi
if [ -e "$build/man/lic3d.1.gz" ]; then
  expect share/man/man1/lic3d.1.gz
  gzip -dc "$usr/share/man/man1/lic3d.1.gz" | grep -q 'lic3d render' ||
    fail "the man page lic3d.1 does not describe lic3d render"
  if [ -x "$build/lic3d-view" ]; then
    expect share/man/man1/lic3d-view.1.gz
  fi
fi
if [ -n "$(find "$build/lib" -name Lic3D.so 2>/dev/null)" ]; then
  [ -n "$(find "$usr/lib" -path '*/paraview-*/plugins/Lic3D/Lic3D.so')" ] ||
    fail "the ParaView plugin Lic3D.so is not installed"
fi
# No headers or static libraries, in the packages or from a plain `cmake --install`.
"$cmake" --install "$build" --prefix "$work/plain" >"$work/install.log" 2>&1 || {
  cat "$work/install.log" >&2
  fail "cmake --install failed"
}
nothing=$(find "$root" "$work/plain" -name include -o -name '*.a' -o -name '*.h')
[ -z "$nothing" ] || fail "headers or static libraries installed: $nothing"

# The installed program, as its users run it.
version=$(dpkg-query --admindir="$root/var/lib/dpkg" -W -f='${Version}' lic3d)
[ "$("$usr/bin/lic3d" --version)" = "lic3d $version" ] ||
  fail "lic3d --version says '$("$usr/bin/lic3d" --version)', the package $version"
VK_DRIVER_FILES=$icd LIC3D_VALIDATION=1 "$usr/bin/lic3d" render --grid 24 --width 96 \
  --height 96 -q -o "$work/x.png" || fail "lic3d render failed ($?)"
[ "$(head -c 4 "$work/x.png" | od -An -c | tr -d ' ')" = "211PNG" ] ||
  fail "lic3d render wrote no PNG"

# Completion from the installed files: commands, then the flags the binary lists.
if command -v bash >/dev/null; then
  words=$(PATH="$usr/bin:$PATH" bash -c '. "$1"
    COMP_WORDS=(lic3d re); COMP_CWORD=1; _lic3d; echo "${COMPREPLY[*]}"
    COMP_WORDS=(lic3d render --kern); COMP_CWORD=2; _lic3d; echo "${COMPREPLY[*]}"' \
    sh "$usr/share/bash-completion/completions/lic3d")
  [ "$words" = "render render2d
--kernel" ] || fail "bash completion gave: $words"
fi

# The Python module, where it was built, imported by Debian's python3 (the one it is built for).
module=$(find "$usr/lib" -path '*python3*' -name 'lic3d*.so' | head -n 1)
if [ -n "$module" ] && /usr/bin/python3 -c 'import numpy' 2>/dev/null; then
  PYTHONPATH=$(dirname "$module") /usr/bin/python3 -c 'import lic3d' ||
    fail "import lic3d failed from $(dirname "$module")"
  echo "package.deb: import lic3d from $(dirname "$module" | sed "s|^$root||")"
fi
echo "package.deb: installed into a scratch root, lic3d render ran"
