#!/bin/sh
# Make sure the HDF5 C library that `cargo build` links (crate hdf5-metno,
# used for the .h5 results) is installed. Idempotent; run it before cargo:
#
#   scripts/ensure-hdf5.sh && cargo build --release
#
# - HDF5 found (pkg-config, or Debian's serial header): nothing to do.
# - Not found, running as root with apt-get: installs libhdf5-dev and
#   pkg-config quietly (Debian/Ubuntu).
# - Otherwise: prints what to do and exits 1.
#
# No environment variable is needed afterwards: hdf5-metno finds Debian's
# serial HDF5 (/usr/lib/x86_64-linux-gnu/hdf5/serial) through pkg-config,
# or through its built-in default paths when pkg-config is absent.
# HDF5 >= 1.10.7 is required (the writer turns file locking off).
set -eu

have_hdf5() {
    if command -v pkg-config >/dev/null 2>&1 && pkg-config --exists hdf5 2>/dev/null; then
        return 0
    fi
    [ -f /usr/include/hdf5/serial/hdf5.h ] && return 0
    # a user-provided installation (see the message below)
    [ -n "${HDF5_DIR:-}" ] && [ -f "${HDF5_DIR}/include/hdf5.h" ] && return 0
    return 1
}

if have_hdf5; then
    exit 0
fi

if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing libhdf5-dev (Debian) for HDF5 output"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null
    apt-get install -y -qq --no-install-recommends libhdf5-dev pkg-config >/dev/null
    if have_hdf5; then
        exit 0
    fi
    echo "error: libhdf5-dev was installed but HDF5 is still not found" >&2
    exit 1
fi

cat >&2 <<'EOF'
error: the HDF5 C library (headers and libhdf5) was not found; fvc writes its
results with it. Either
  - install it with the system package manager, e.g. as root on Debian/Ubuntu:
        apt-get install -y libhdf5-dev pkg-config
    (Fedora: dnf install hdf5-devel; macOS: brew install hdf5), or
  - point HDF5_DIR at an installation (HDF5_DIR/include/hdf5.h, HDF5_DIR/lib), or
  - build HDF5 from source together with fvc, without root: that needs
    cmake >= 3.26 (e.g. `pip install --user cmake`) and a C compiler; add
        --features solver-app/hdf5-static
    to the cargo command, e.g.
        cargo test --workspace --release --features solver-app/hdf5-static
    (adds about 2 minutes to a clean build).
EOF
exit 1
