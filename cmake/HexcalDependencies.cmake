# Every third-party package hexcal uses, found once here (Debian bookworm packages;
# scripts/install-deps.sh installs them). Layers link only what docs/architecture.md allows.
find_package(Threads REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Ceres REQUIRED)
# nlopt.hpp is a header-only C++ wrapper over the C library, which holds SLSQP.
find_package(NLopt REQUIRED)
find_package(GTest REQUIRED)
if(HEXCAL_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()

# Vision and GUI stacks. Found from the start so that a missing or broken package
# fails at configure time, not when the vision/ui layers land.
# videoio: the GUI's camera capture (ui/measure_recording.cc).
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs calib3d videoio)
# Debian's libapriltag-dev ships only a pkg-config file.
find_package(PkgConfig REQUIRED)
pkg_check_modules(APRILTAG REQUIRED IMPORTED_TARGET apriltag)
# The log lines of FFmpeg and GLib (GStreamer), which OpenCV's videoio loads:
# kept off stderr unless hexcal --verbose (vision/library_logs.h). Optional:
# without their headers those lines come through as they did.
pkg_check_modules(AVUTIL IMPORTED_TARGET libavutil)
pkg_check_modules(GLIB IMPORTED_TARGET glib-2.0)
# GenICam cameras (the aravis: camera, devices/aravis_frame_source.h) and the
# fake GigE Vision camera of the tests: optional. Without it hexcal builds and
# refuses aravis: URLs, saying what to install.
set(HEXCAL_HAVE_ARAVIS OFF)
if(HEXCAL_WITH_ARAVIS)
  pkg_check_modules(ARAVIS IMPORTED_TARGET aravis-0.8)
  if(ARAVIS_FOUND)
    set(HEXCAL_HAVE_ARAVIS ON)
  else()
    message(STATUS "Aravis 0.8 not found: aravis: cameras are refused (install libaravis-dev: scripts/install-deps.sh)")
  endif()
endif()
find_package(Qt5 5.15 REQUIRED COMPONENTS Widgets Charts Svg)
# Debian's VTK 9.1 config references MPI::MPI_C: find MPI (C enabled) first.
find_package(MPI COMPONENTS C)
find_package(VTK 9 REQUIRED COMPONENTS GUISupportQt RenderingOpenGL2 RenderingCore
             InteractionStyle CommonCore FiltersSources FiltersCore)

# yaml-cpp 0.7 on bookworm exports the target as "yaml-cpp" without a namespace.
if(TARGET yaml-cpp AND NOT TARGET yaml-cpp::yaml-cpp)
  add_library(yaml-cpp::yaml-cpp ALIAS yaml-cpp)
endif()
