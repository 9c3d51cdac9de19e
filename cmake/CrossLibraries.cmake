# A cross build (the aarch64 preset) links only libraries of its own architecture: from the
# target's sysroot (scripts/sysroot-arm64.sh) or the cross toolchain. Package mode BOTH, which
# lets header-only packages (Eigen, CLI11, nlohmann_json) come from the host, would otherwise also
# take a host package whose -dev is missing from the sysroot (apriltag's config names the x86-64
# library), and the link would fail much later with "file in wrong format".

set(colag_compiled_packages CycloneDDS GTest benchmark apriltag yaml-cpp)

# Before the packages are found: a package directory cached from an earlier configure (before
# the sysroot was complete) that points into the host is forgotten, so that it is searched anew.
function(colag_forget_host_packages)
  foreach(pkg ${colag_compiled_packages})
    if(DEFINED ${pkg}_DIR AND ${pkg}_DIR AND NOT "${${pkg}_DIR}" MATCHES "^${COLAG_SYSROOT}/")
      unset(${pkg}_DIR CACHE)
    endif()
  endforeach()
endfunction()

# After: every library file of these imported targets must lie in the sysroot or the toolchain.
function(colag_check_cross_libraries)
  set(allowed "^(${COLAG_SYSROOT}|/usr/aarch64-linux-gnu|/usr/lib/gcc-cross)/")
  foreach(target ${ARGN})
    if(NOT TARGET ${target})
      continue()
    endif()
    set(files "")
    foreach(property IMPORTED_LOCATION IMPORTED_LOCATION_NONE IMPORTED_LOCATION_RELEASE
                     IMPORTED_LOCATION_RELWITHDEBINFO IMPORTED_LOCATION_DEBUG
                     INTERFACE_LINK_LIBRARIES)
      get_target_property(value ${target} ${property})
      if(value)
        list(APPEND files ${value})
      endif()
    endforeach()
    foreach(file ${files})
      if(file MATCHES "^/" AND NOT file MATCHES "${allowed}")
        foreach(pkg ${colag_compiled_packages})
          unset(${pkg}_DIR CACHE)  # so that the next configure searches again
        endforeach()
        message(FATAL_ERROR
          "cross build: ${target} resolves to ${file}, which is not in the target's sysroot "
          "(${COLAG_SYSROOT}) nor the cross toolchain: a host library. Its package is missing "
          "from the sysroot: run scripts/sysroot-arm64.sh (it lists the packages), then "
          "configure again.")
      endif()
    endforeach()
  endforeach()
endfunction()
