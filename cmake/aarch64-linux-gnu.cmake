# Cross-compiles for aarch64 Linux with Debian's g++-aarch64-linux-gnu against
# the arm64 multiarch packages (libgtest-dev:arm64, ...), and runs what it
# builds (test discovery, ctest) under qemu-user. scripts/test-portability.sh.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# Multiarch: headers in /usr/include, libraries and package configs in
# /usr/lib/aarch64-linux-gnu; the host's x86-64 ones must not be picked up.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig)
# The dynamic loader and libc of the cross toolchain; the other arm64
# libraries qemu then finds in /usr/lib/aarch64-linux-gnu.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)
