#!/bin/sh
# Installs the built tree into a temporary prefix, then builds and runs a program
# against it three ways: find_package(fbrl) shared, static, and pkg-config.
set -eu
build=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
cmake -S "$src/tests/install" -B "$tmp/cm" -DCMAKE_PREFIX_PATH="$tmp/prefix" >/dev/null
cmake --build "$tmp/cm" >/dev/null
LD_LIBRARY_PATH="$tmp/prefix/lib:$tmp/prefix/lib64${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$tmp/cm/consumer_shared"
"$tmp/cm/consumer_static"
pcdir=$(dirname "$(find "$tmp/prefix" -name fbrl.pc | head -n 1)")
flags=$(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags --libs fbrl)
# shellcheck disable=SC2086
cc -std=c99 -o "$tmp/consumer_pc" "$src/tests/install/consumer.c" $flags
LD_LIBRARY_PATH="$tmp/prefix/lib:$tmp/prefix/lib64" "$tmp/consumer_pc"
echo "install test: find_package (shared, static) and pkg-config consumers ran"
