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
# The loader and libc are multiarch libc6:arm64's (/lib/ld-linux-aarch64.so.1),
# as for every other arm64 library. Not `-L /usr/aarch64-linux-gnu` (the cross
# toolchain's libc): mixed with the multiarch libraries, its first thread
# never started, and any program with a thread pool hung at start.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64)
