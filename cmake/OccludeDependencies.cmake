# Finds every dependency; a missing required one stops configuration with the
# Debian package to install (scripts/demo and scripts/test install them all).
function(occlude_missing what debian_package)
  message(FATAL_ERROR
    "occlude: required dependency '${what}' not found.\n"
    "  Fix: sudo apt-get install ${debian_package}\n"
    "  (or run scripts/test, which installs every missing package)")
endfunction()

find_package(Eigen3 3.3 QUIET NO_MODULE)
if(NOT TARGET Eigen3::Eigen)
  occlude_missing("Eigen3" "libeigen3-dev")
endif()

find_package(NLopt QUIET CONFIG)
if(NOT TARGET NLopt::nlopt AND NOT TARGET NLopt::nlopt_cxx)
  occlude_missing("NLopt" "libnlopt-cxx-dev")
endif()
if(TARGET NLopt::nlopt_cxx)
  set(OCCLUDE_NLOPT_TARGET NLopt::nlopt_cxx)
else()
  set(OCCLUDE_NLOPT_TARGET NLopt::nlopt)
endif()

find_package(Ceres QUIET CONFIG)
if(NOT Ceres_FOUND)
  occlude_missing("Ceres" "libceres-dev")
endif()

find_package(assimp QUIET CONFIG)
if(NOT TARGET assimp::assimp)
  occlude_missing("assimp" "libassimp-dev")
endif()

# OpenCV: the CMake package comes only with the large libopencv-dev meta package, so the parts
# are found directly. occlude::opencv is core and imgproc (the report's and charts' drawing);
# the image codecs (imgcodecs) are the tests' alone, to decode what the app writes: linked into
# `occlude`, their dependencies (GDAL, GDCM, Poppler, ...) cost each run about 0.1 s and 50 MB
# before main (docs/results/speed/README.md), so the app writes PNG with zlib (base/png_writer.h).
find_path(OCCLUDE_OPENCV_INCLUDE opencv2/core.hpp PATH_SUFFIXES opencv4)
if(NOT OCCLUDE_OPENCV_INCLUDE)
  occlude_missing("OpenCV core headers" "libopencv-core-dev")
endif()
foreach(part core imgproc imgcodecs)
  find_library(OCCLUDE_OPENCV_${part} opencv_${part})
  if(NOT OCCLUDE_OPENCV_${part})
    occlude_missing("OpenCV ${part}" "libopencv-${part}-dev")
  endif()
endforeach()
add_library(occlude_opencv INTERFACE)
target_include_directories(occlude_opencv SYSTEM INTERFACE ${OCCLUDE_OPENCV_INCLUDE})
target_link_libraries(occlude_opencv INTERFACE ${OCCLUDE_OPENCV_imgproc} ${OCCLUDE_OPENCV_core})
add_library(occlude::opencv ALIAS occlude_opencv)
add_library(occlude_opencv_codecs INTERFACE)
target_link_libraries(occlude_opencv_codecs INTERFACE ${OCCLUDE_OPENCV_imgcodecs} occlude_opencv)
add_library(occlude::opencv_codecs ALIAS occlude_opencv_codecs)

find_package(ZLIB QUIET)
if(NOT TARGET ZLIB::ZLIB)
  occlude_missing("zlib" "zlib1g-dev")
endif()

find_package(tomlplusplus QUIET CONFIG)
if(NOT TARGET tomlplusplus::tomlplusplus)
  occlude_missing("toml++" "libtomlplusplus-dev")
endif()
find_package(nlohmann_json QUIET CONFIG)
if(NOT TARGET nlohmann_json::nlohmann_json)
  occlude_missing("nlohmann-json" "nlohmann-json3-dev")
endif()
find_package(CLI11 QUIET CONFIG)
if(NOT TARGET CLI11::CLI11)
  occlude_missing("CLI11" "libcli11-dev")
endif()
find_package(Threads REQUIRED)

if(OCCLUDE_BUILD_TESTS)
  find_package(GTest QUIET CONFIG)
  if(NOT TARGET GTest::gtest_main)
    find_package(GTest QUIET)
  endif()
  if(NOT TARGET GTest::gtest_main)
    occlude_missing("GoogleTest" "libgtest-dev libgmock-dev")
  endif()
endif()

# Optional, benchmarks only.
find_package(benchmark QUIET CONFIG)
find_package(fcl QUIET CONFIG)
if(TARGET fcl)
  set(OCCLUDE_HAVE_FCL ON)
  message(STATUS "occlude: FCL found: the bench command compares against it")
else()
  set(OCCLUDE_HAVE_FCL OFF)
  message(STATUS "occlude: FCL not found (optional, apt-get install libfcl-dev): bench runs without the peer")
endif()

# OpenVDB: the second peer of `occlude bench` (a sparse narrow-band level set), optional and
# benchmark-only like FCL. Found directly, not through find_package(OpenVDB): Debian's
# FindOpenVDB.cmake insists on Boost iostreams and stops configuration even when asked QUIET.
# OpenVDB 10's headers also include oneTBB's and a few Boost headers (libboost-dev is not a
# dependency of libopenvdb-dev), and Debian's build stores half floats as Imath's (its inline
# conversions need libImath at link time; libimath-dev is a dependency), so all are checked.
find_path(OCCLUDE_OPENVDB_INCLUDE openvdb/openvdb.h)
find_library(OCCLUDE_OPENVDB_LIBRARY openvdb)
find_path(OCCLUDE_BOOST_INCLUDE boost/numeric/conversion/conversion_traits.hpp)
find_library(OCCLUDE_IMATH_LIBRARY NAMES Imath Imath-3_1)
find_package(TBB QUIET CONFIG)
set(OCCLUDE_HAVE_OPENVDB OFF)
if(OCCLUDE_OPENVDB_INCLUDE AND OCCLUDE_OPENVDB_LIBRARY AND OCCLUDE_BOOST_INCLUDE
   AND OCCLUDE_IMATH_LIBRARY AND TARGET TBB::tbb)
  add_library(occlude_openvdb INTERFACE)
  target_include_directories(occlude_openvdb SYSTEM INTERFACE
    ${OCCLUDE_OPENVDB_INCLUDE} ${OCCLUDE_BOOST_INCLUDE})
  target_link_libraries(occlude_openvdb INTERFACE
    ${OCCLUDE_OPENVDB_LIBRARY} ${OCCLUDE_IMATH_LIBRARY} TBB::tbb)
  add_library(occlude::openvdb ALIAS occlude_openvdb)
  set(OCCLUDE_HAVE_OPENVDB ON)
  message(STATUS "occlude: OpenVDB found: the bench command compares against its level sets")
else()
  set(missing "")
  if(NOT OCCLUDE_OPENVDB_INCLUDE OR NOT OCCLUDE_OPENVDB_LIBRARY)
    list(APPEND missing "OpenVDB")
  endif()
  if(NOT OCCLUDE_IMATH_LIBRARY)
    list(APPEND missing "Imath")
  endif()
  if(NOT OCCLUDE_BOOST_INCLUDE)
    list(APPEND missing "Boost headers")
  endif()
  if(NOT TARGET TBB::tbb)
    list(APPEND missing "oneTBB")
  endif()
  list(JOIN missing ", " missing)
  message(STATUS "occlude: OpenVDB peer off (${missing} not found; optional, "
                 "apt-get install libopenvdb-dev libboost-dev): bench runs without it")
endif()
