# Third-party packages of the quiver library (Debian 12, ../shared/STACK.md).
# Included by the build and by the installed quiverConfig.cmake.
# OpenImageIO is not among them: only the quiver_oiio module links it.
find_package(PNG REQUIRED)                # PNG::PNG, io/image_output.cpp
find_package(OpenEXR CONFIG REQUIRED)     # OpenEXR::OpenEXR, io/image_output.cpp
find_package(TBB CONFIG REQUIRED)
find_package(tomlplusplus CONFIG REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)  # app/stats_json.cpp
# cpp-httplib, app/view_server.cpp: Debian builds it as a library (its
# header declares, libcpp-httplib.so defines), described by pkg-config.
find_package(PkgConfig REQUIRED)
pkg_check_modules(CPP_HTTPLIB REQUIRED IMPORTED_TARGET GLOBAL cpp-httplib)
