# Cross-compiling for aarch64 Linux robot boards (Debian's crossbuild-essential-arm64).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

# Target libraries come from a sysroot folder of unpacked arm64 .debs (never a multiarch install
# on the host). Default: build/sysroot-arm64 beside the build trees; override with COLAG_SYSROOT.
if(NOT DEFINED COLAG_SYSROOT)
  get_filename_component(COLAG_SYSROOT "${CMAKE_CURRENT_LIST_DIR}/../build/sysroot-arm64" ABSOLUTE)
endif()
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES COLAG_SYSROOT)  # the compiler checks read it too
# Without a complete sysroot, stop before anything is searched: a package found on the host now
# would stay in the cache after the sysroot appears (cmake/CrossLibraries.cmake checks the rest).
if(NOT EXISTS "${COLAG_SYSROOT}/.complete")
  message(FATAL_ERROR "aarch64: no complete sysroot in ${COLAG_SYSROOT}: run "
                      "scripts/sysroot-arm64.sh first (or set COLAG_SYSROOT)")
endif()
set(CMAKE_FIND_ROOT_PATH "${COLAG_SYSROOT}" /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
# BOTH: header-only packages (Eigen) are architecture-independent and may come from the host.
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
if(EXISTS "${COLAG_SYSROOT}")
  # scripts/sysroot-arm64.sh lists every folder with shared libraries in rpath-link.txt.
  set(colag_link_dirs lib/aarch64-linux-gnu usr/lib/aarch64-linux-gnu)
  if(EXISTS "${COLAG_SYSROOT}/rpath-link.txt")
    file(STRINGS "${COLAG_SYSROOT}/rpath-link.txt" colag_link_dirs)
  endif()
  set(colag_link_flags "")
  foreach(dir ${colag_link_dirs})
    string(APPEND colag_link_flags " -Wl,-rpath-link,${COLAG_SYSROOT}/${dir}")
  endforeach()
  set(CMAKE_EXE_LINKER_FLAGS_INIT "${colag_link_flags}")  # set, not append: read more than once
  include_directories(SYSTEM "${COLAG_SYSROOT}/usr/include/aarch64-linux-gnu")
endif()

# binfmt_misc is not mounted on the build machines: ctest runs target programs through qemu.
# The sysroot's shared libraries are found through LD_LIBRARY_PATH inside the emulated process.
set(colag_library_path "${COLAG_SYSROOT}/lib/aarch64-linux-gnu:${COLAG_SYSROOT}/usr/lib/aarch64-linux-gnu")
foreach(dir ${colag_link_dirs})
  string(APPEND colag_library_path ":${COLAG_SYSROOT}/${dir}")
endforeach()
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64-static;-L;/usr/aarch64-linux-gnu;-E;
    LD_LIBRARY_PATH=${colag_library_path})
