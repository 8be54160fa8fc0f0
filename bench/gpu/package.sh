#!/usr/bin/env bash
# Packages the host build of pcrf for the lent GPU machine (docs/gpu.md, "Measuring"): that
# machine's image has CUDA's nvcc and CMake but none of Debian's -dev or run-time packages, so
# the engine built here travels with every shared library it loads. Not a test.
#
#   bench/gpu/package.sh [--build DIR] [--dest DIR] [--records DIR] [--check]
#
# BUILD (default build/) should be configured with -DPCRF_CUDA=ON where nvcc is here (a
# CUDA 13 toolkit builds for the H100/H200's sm_90; the driver there, 580, runs CUDA 13):
#   cmake -S . -B build-cuda -DCMAKE_BUILD_TYPE=Release -DPCRF_CUDA=ON
#   cmake --build build-cuda -j2 --target pcrf pcrf_gpu_bench test_gpu
#   bench/gpu/package.sh --build build-cuda --check
# A build without CUDA packages too (its --device gpu is then the error).
#
# DEST (default .gpu-pkg in the checkout, ignored by git; the device tool carries it when its
# `carry` names it) then holds:
#   bin/       pcrf, pcrf_gpu_bench, test_gpu (the gpu-labelled test) where built, Open MPI's
#              mpirun (orterun), orted, ompi_info
#   lib/       the ldd closure of all of them and of every Open MPI and PMIx plugin, glibc's
#              own libraries left out (the image has a glibc at least as new) and the CUDA
#              driver's (libcuda: the machine's own); libstdc++ and libgcc_s apart in
#              lib/fallback, used only where the image's are older; CUDA's runtime included
#   ompi/      Open MPI's plugin folder (lib/openmpi3), help and data files (share/openmpi),
#              its mca-params file (etc), found through OPAL_PREFIX and the OPAL_* folders
#   pmix2/     PMIx's plugins, help files and params (PMIX_INSTALL_PREFIX)
#   hdf5/      HDF5's filter plugin folder (HDF5_PLUGIN_PATH; empty where Debian has none)
#   records/paper/  ER1 and ER7 of the paper (gpu_measure.py's workload and test_gpu's record;
#              PCRF_RECORDS_DIR points here), from --records
#   env.sh     `source` it: PATH, LD_LIBRARY_PATH, OPAL_*, PMIX_*, Open MPI's MCA choices for
#              one node (shared memory, no network transport), root allowed
#   COMMIT     the commit it was built from
# It fails if DEST grows past 60 MiB (the tool carries 64 MiB with the working tree).
#
# --check: runs the packaged pcrf (one rank, and 2 ranks under the packaged mpirun) from a
# clean environment (env -i), in a mount namespace where every library the package holds,
# Open MPI's and PMIx's folders are hidden from their system places, so that a missing piece
# fails here as it would there.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build="$root/build"
dest="$root/.gpu-pkg"
records="${PCRF_RECORDS_DIR:+$PCRF_RECORDS_DIR/paper}"
[ -n "$records" ] || records="$root/../shared/records/paper"
check=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build=$(cd "$2" && pwd); shift 2 ;;
    --dest) dest="$2"; shift 2 ;;
    --records) records="$2"; shift 2 ;;
    --check) check=1; shift ;;
    *) echo "package.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
limit_bytes=$((60 * 1024 * 1024))

# glibc's own libraries: the image's are used (never carry a libc: it must match ld.so).
is_glibc() {
  case "$(basename "$1")" in
    libc.so.*|libm.so.*|libpthread.so.*|libdl.so.*|librt.so.*|libresolv.so.*|libutil.so.*|ld-linux*|libanl.so.*|libmvec.so.*) return 0 ;;
    libcuda.so.*|libnvidia-*.so.*) return 0 ;;  # the driver's: it must match the machine's kernel module
  esac
  return 1
}

# The libraries `ldd` resolves for each file given, one path a line.
closure() { ldd "$@" 2>/dev/null | awk '/=> \// {print $3}' | sort -u; }

make_package() {
  [ -x "$build/pcrf" ] || { echo "package.sh: no $build/pcrf: build first" >&2; exit 2; }
  local bench="$build/bench/gpu/pcrf_gpu_bench"
  [ -x "$bench" ] || { echo "package.sh: no $bench: build the pcrf_gpu_bench target" >&2; exit 2; }
  case "$dest" in /*) ;; *) dest="$PWD/$dest" ;; esac
  rm -rf "$dest"
  mkdir -p "$dest"/{bin,lib/fallback,ompi/lib,ompi/share,ompi/etc,pmix2/lib,pmix2/share,hdf5/plugins,records/paper}

  local pkglibdir pkgdatadir sysconfdir
  pkglibdir=$(ompi_info --parsable --path pkglibdir | cut -d: -f3)
  pkgdatadir=$(ompi_info --parsable --path pkgdatadir | cut -d: -f3)
  sysconfdir=$(ompi_info --parsable --path sysconfdir | cut -d: -f3)
  cp "$build/pcrf" "$bench" "$dest/bin/"
  [ -x "$build/tests/test_gpu" ] && cp "$build/tests/test_gpu" "$dest/bin/"
  for tool in mpirun orted ompi_info; do
    cp "$(readlink -f "$(command -v $tool)")" "$dest/bin/$tool"
  done
  # Open MPI's plugins, but not the network transports of clusters (UCX, OFI, verbs, PSM,
  # Portals): one node talks through shared memory, and their libraries would outgrow the limit.
  mkdir -p "$dest/ompi/lib/$(basename "$pkglibdir")"
  for plugin in "$pkglibdir"/*.so; do
    case "$(basename "$plugin")" in *ucx*|*ofi*|*openib*|*verbs*|*psm*|*portals*|*java*) continue ;; esac
    cp "$plugin" "$dest/ompi/lib/$(basename "$pkglibdir")/"
  done
  cp -r "$pkgdatadir" "$dest/ompi/share/"
  cp -r "$sysconfdir"/. "$dest/ompi/etc/"
  # PMIx (Open MPI 4 uses Debian's external PMIx): its plugin folder and share.
  local pmix_lib
  pmix_lib=$(closure "$dest/bin/mpirun" "$dest/ompi/lib/$(basename "$pkglibdir")"/*.so | grep 'libpmix\.so' | head -1 || true)
  if [ -n "$pmix_lib" ]; then
    local pmix_root
    pmix_root=$(dirname "$(dirname "$(readlink -f "$pmix_lib")")")
    [ -d "$pmix_root/lib/pmix" ] || pmix_root=$(dirname "$(readlink -f "$pmix_lib")")/pmix2
    if [ -d "$pmix_root/lib/pmix" ]; then
      cp -r "$pmix_root/lib/pmix" "$dest/pmix2/lib/"
      [ -d "$pmix_root/share" ] && cp -r "$pmix_root/share/." "$dest/pmix2/share/"
    fi
  fi
  # HDF5's filter plugins, where the system has a folder of them.
  for plugins in /usr/lib/x86_64-linux-gnu/hdf5/openmpi/plugins /usr/lib/x86_64-linux-gnu/hdf5/plugins; do
    [ -d "$plugins" ] && cp -r "$plugins/." "$dest/hdf5/plugins/" && break
  done

  # The ldd closure of everything that runs, under the names the loader looks for.
  local elves=("$dest"/bin/* "$dest"/ompi/lib/*/*.so)
  [ -d "$dest/pmix2/lib/pmix" ] && elves+=("$dest"/pmix2/lib/pmix/*.so)
  [ -n "$(ls -A "$dest/hdf5/plugins")" ] && elves+=("$dest"/hdf5/plugins/*.so)
  local missing
  missing=$(ldd "${elves[@]}" 2>/dev/null | grep 'not found' | sort -u || true)
  [ -z "$missing" ] || { echo "package.sh: libraries not found here:" >&2; echo "$missing" >&2; exit 1; }
  while read -r lib; do
    is_glibc "$lib" && continue
    local name target
    name=$(basename "$lib")
    target="$dest/lib"
    case "$name" in libstdc++.so.*|libgcc_s.so.*) target="$dest/lib/fallback" ;; esac
    cp -L "$lib" "$target/$name"
  done < <(closure "${elves[@]}")
  # Open MPI's own libraries also where OPAL_LIBDIR points (its plugins look there).
  for name in libmpi.so.40 libopen-rte.so.40 libopen-pal.so.40; do
    [ -f "$dest/lib/$name" ] && ln -sf "../../lib/$name" "$dest/ompi/lib/$name"
  done
  # The GLIBCXX version the packaged programs need: env.sh uses lib/fallback where the image's
  # libstdc++ lacks it.
  objdump -T "$dest"/bin/* "$dest"/lib/*.so* 2>/dev/null | grep -o 'GLIBCXX_[0-9.]*' | sort -uV | tail -1 > "$dest/lib/fallback/GLIBCXX_NEEDED"

  for r in ER1_MUL279.AT2 ER7_CAP000.AT2; do
    if [ -f "$records/$r" ]; then cp "$records/$r" "$dest/records/paper/"; else echo "package.sh: note: no $records/$r" >&2; fi
  done
  (cd "$root" && echo "$(git rev-parse --short HEAD)$(git diff --quiet HEAD -- . ':!.gpu-pkg' || echo '+changes')") > "$dest/COMMIT"
  write_env
  local bytes
  bytes=$(du -sb "$dest" | cut -f1)
  local cuda="without CUDA"
  ls "$dest/lib" | grep -q '^libcudart' && cuda="with CUDA's runtime $(ls "$dest/lib" | grep '^libcudart' | head -1)"
  echo "package.sh: $dest: $((bytes / 1024 / 1024)) MiB ($(ls "$dest/lib" | wc -l) libraries, $cuda), commit $(cat "$dest/COMMIT")"
  if [ "$bytes" -gt "$limit_bytes" ]; then
    echo "package.sh: over the 60 MiB the device tool leaves beside the working tree" >&2
    exit 1
  fi
}

write_env() {
  local plugins
  plugins=$(basename "$(ompi_info --parsable --path pkglibdir | cut -d: -f3)")
  cat > "$dest/env.sh" <<EOF
# Source this (bash): the packaged pcrf and Open MPI, wherever this folder lies.
pkg=\$(cd "\$(dirname "\${BASH_SOURCE[0]}")" && pwd)
export PATH="\$pkg/bin:\$PATH"
libs="\$pkg/lib:\$pkg/ompi/lib"
# libstdc++/libgcc_s of the build machine only where the image's are older than needed.
needed=\$(cat "\$pkg/lib/fallback/GLIBCXX_NEEDED" 2>/dev/null)
system=\$(/sbin/ldconfig -p 2>/dev/null | awk '/libstdc\+\+\.so\.6 .*x86-64/ {print \$NF; exit}')
if [ -z "\$system" ] || ! grep -q -a "\$needed" "\$system" 2>/dev/null; then libs="\$libs:\$pkg/lib/fallback"; fi
export LD_LIBRARY_PATH="\$libs\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
# Open MPI relocated (its compiled-in folders are Debian's): every folder it looks in.
export OPAL_PREFIX="\$pkg/ompi" OPAL_EXEC_PREFIX="\$pkg/ompi" OPAL_BINDIR="\$pkg/bin" OPAL_LIBDIR="\$pkg/ompi/lib"
export OPAL_PKGLIBDIR="\$pkg/ompi/lib/$plugins" OPAL_DATAROOTDIR="\$pkg/ompi/share" OPAL_DATADIR="\$pkg/ompi/share"
export OPAL_PKGDATADIR="\$pkg/ompi/share/openmpi" OPAL_SYSCONFDIR="\$pkg/ompi/etc"
export PMIX_INSTALL_PREFIX="\$pkg/pmix2" PMIX_MCA_mca_base_component_path="\$pkg/pmix2/lib/pmix"
export HDF5_PLUGIN_PATH="\$pkg/hdf5/plugins" PCRF_RECORDS_DIR="\$pkg/records"
# One node: shared memory between ranks, no network transport; no single-copy (ptrace-based
# CMA is refused in some sandboxes); root allowed (the lent machine runs commands as root).
export OMPI_MCA_pml=ob1 OMPI_MCA_btl=self,vader OMPI_MCA_osc=sm,pt2pt OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
unset needed system libs
EOF
}

# The packaged pcrf from a clean environment, with the system's copies of what the package
# holds hidden (a private mount namespace: nothing outside this process tree sees it).
check_package() {
  case "$dest" in /*) ;; *) dest="$PWD/$dest" ;; esac
  local work
  work=$(mktemp -d /tmp/gpu_pkg_check.XXXXXX)
  cat > "$work/hide_and_run.sh" <<'EOF'
set -eu
pkg=$1; work=$2
for lib in "$pkg"/lib/*.so* "$pkg"/lib/fallback/*.so*; do
  name=$(basename "$lib")
  for dir in /lib/x86_64-linux-gnu /usr/lib/x86_64-linux-gnu /usr/lib/x86_64-linux-gnu/openmpi/lib /usr/local/cuda/lib /usr/local/cuda/lib64; do
    [ -e "$dir/$name" ] && mount --bind /dev/null "$(readlink -f "$dir/$name")"
  done
done
for dir in /usr/lib/x86_64-linux-gnu/openmpi /usr/share/openmpi /etc/openmpi /usr/lib/x86_64-linux-gnu/pmix2; do
  [ -d "$dir" ] && mount -t tmpfs none "$dir"
done
cd "$work"
env -i HOME="$work" PATH=/usr/bin:/bin bash -c '
  set -e
  source "$0/env.sh"
  command -v pcrf
  pcrf study study.toml -o one.h5 --progress-interval 0
  mpirun -n 2 pcrf study study.toml -o two.h5 --progress-interval 0
  pcrf cube info two.h5 | head -3
  mpirun -n 2 pcrf_gpu_bench study.toml --backend cpu --cases 40 --group 8 | head -2
  pcrf_gpu_bench study.toml --backend gpu || test $? -eq 3
  if command -v test_gpu >/dev/null; then PCRF_GPU_TEST_CASES=50 test_gpu || test $? -eq 77; fi
' "$pkg"
EOF
  printf '[[records]]\nsynthetic = ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=3"]\n[axes]\nkappa = [1.5, 2.0, 2.5]\n' > "$work/study.toml"
  echo "package.sh: checking $dest from a clean environment, system copies hidden"
  if unshare -m --propagation private bash "$work/hide_and_run.sh" "$dest" "$work"; then
    echo "package.sh: check passed"
    rm -rf "$work"
  else
    echo "package.sh: check FAILED (scratch kept in $work)" >&2
    exit 1
  fi
}

make_package
[ "$check" -eq 0 ] || check_package
