# bench/siconos_peer.bash - sourced by the benchmarks that run a Siconos peer (siconos.sh, network.sh, lcs.sh,
# contact.sh): builds bench/NAME.cpp against Siconos' kernel (libsiconos-kernel-dev) into $build/bench/NAME
# with the flags every peer takes. Needs $build and the repository as the working directory.
build_siconos_peer() {
  mkdir -p "$build/bench"
  c++ -O2 -std=c++17 -Wall -Wextra -Werror -isystem /usr/include/siconos -isystem /usr/include/siconos/kernel \
    -isystem /usr/include/siconos/numerics "bench/$1.cpp" -o "$build/bench/$1" -lsiconos_kernel -lsiconos_numerics
}
