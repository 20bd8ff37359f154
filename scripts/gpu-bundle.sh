#!/bin/sh
# Packs a built `kiri` with every shared library it loads (not the GL ones: the GPU's driver
# brings those) and PROJ's database into one archive, to run the benches on a machine with a GPU
# that has none of kiri's Debian packages (docs/speed.md, "On a GPU").
#
#   sh scripts/gpu-bundle.sh build/release .gpu/kiri.tar.xz
#
# On that machine: tar xJf kiri.tar.xz -C DIR, then DIR/run kiri ARGS... runs it on the bundled
# libraries; the bundle's own C library is used only where the machine's is older than the one
# kiri was built with.
set -eu
BUILD=${1:?usage: gpu-bundle.sh BUILD_DIR ARCHIVE}
ARCHIVE=${2:?usage: gpu-bundle.sh BUILD_DIR ARCHIVE}
KIRI="$BUILD/apps/kiri/kiri"
[ -x "$KIRI" ] || { echo "gpu-bundle: $KIRI: not built" >&2; exit 2; }
STAGE=$(mktemp -d)
trap 'rm -rf "$STAGE"' EXIT
mkdir -p "$STAGE/bin" "$STAGE/lib" "$STAGE/libc" "$STAGE/proj"
cp "$KIRI" "$STAGE/bin/"
# GL comes from the machine's driver (glvnd's libEGL and the vendor's library), libc apart.
ldd "$KIRI" | awk '/=>/ {print $3}' | while read -r lib; do
  case "$(basename "$lib")" in
    libEGL*|libGL*|libOpenGL*|libgbm*|libdrm*|libvulkan*) ;;
    libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*|libmvec.so*) cp -L "$lib" "$STAGE/libc/" ;;
    *) cp -L "$lib" "$STAGE/lib/" ;;
  esac
done
cp -L /lib64/ld-linux-x86-64.so.2 "$STAGE/libc/"
strip --strip-unneeded "$STAGE"/bin/* "$STAGE"/lib/* 2>/dev/null || true
cp /usr/share/proj/proj.db "$STAGE/proj/"
GLIBC=$(ldd --version | awk 'NR==1 {print $NF}')
cat >"$STAGE/run" <<EOF
#!/bin/sh
# Runs a bundled program: bin/NAME ARGS... on the bundled libraries (built with glibc $GLIBC).
here=\$(cd "\$(dirname "\$0")" && pwd)
name=\$1; shift
export PROJ_DATA="\$here/proj" PROJ_LIB="\$here/proj"
have=\$(ldd --version 2>/dev/null | awk 'NR==1 {print \$NF}')
if [ -n "\$have" ] && [ "\$(printf '%s\n%s\n' "$GLIBC" "\$have" | sort -V | head -1)" = "$GLIBC" ]; then
  LD_LIBRARY_PATH="\$here/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}" exec "\$here/bin/\$name" "\$@"
fi
exec "\$here/libc/ld-linux-x86-64.so.2" --library-path "\$here/lib:\$here/libc:/usr/lib/x86_64-linux-gnu:/usr/local/nvidia/lib64" "\$here/bin/\$name" "\$@"
EOF
chmod +x "$STAGE/run"
mkdir -p "$(dirname "$ARCHIVE")"
tar -C "$STAGE" -cf - . | xz -T2 -6 >"$ARCHIVE"
echo "$ARCHIVE: $(du -h "$ARCHIVE" | cut -f1)"
