# Third-party packages of the quiver library (Debian 12, ../shared/STACK.md).
# Included by the build and by the installed quiverConfig.cmake.
find_package(OpenImageIO CONFIG REQUIRED)
# Debian's OpenImageIO target lists /usr/include/opencv4, which does not exist.
get_target_property(_quiver_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
if(_quiver_oiio_includes)
  list(FILTER _quiver_oiio_includes EXCLUDE REGEX "opencv4")
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_quiver_oiio_includes}")
endif()
find_package(TBB CONFIG REQUIRED)
find_package(tomlplusplus CONFIG REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)  # app/stats_json.cpp
