# Finds individual OpenCV modules (Debian's libopencv-<module>-dev packages) without the
# libopencv-dev meta-package, which pulls in every module and its GUI stack, and defines one
# imported target per module: colag::opencv_<module>.
function(colag_find_opencv)
  find_path(COLAG_OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
  foreach(module ${ARGN})
    string(TOUPPER ${module} upper)
    find_library(COLAG_OPENCV_${upper}_LIBRARY opencv_${module})
    if(COLAG_OPENCV_INCLUDE_DIR AND COLAG_OPENCV_${upper}_LIBRARY AND NOT TARGET colag::opencv_${module})
      add_library(colag::opencv_${module} UNKNOWN IMPORTED)
      set_target_properties(colag::opencv_${module} PROPERTIES
        IMPORTED_LOCATION ${COLAG_OPENCV_${upper}_LIBRARY}
        INTERFACE_INCLUDE_DIRECTORIES ${COLAG_OPENCV_INCLUDE_DIR})
    endif()
  endforeach()
endfunction()
