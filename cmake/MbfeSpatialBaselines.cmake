# The numerical rigid-body libraries the spatial kernels are compared with
# (tests/generator/spatial_baselines_test.cpp, bench/spatial_baselines_bench.cpp):
#   MuJoCo: Debian's libmujoco-dev (scripts/install-deps.sh), found by its CMake package;
#   RBDL: not packaged by Debian; give the prefix of an installation of it
#         (include/rbdl/rbdl.h, lib/librbdl.so) with -DMBFE_RBDL_DIR=<prefix>.
# Defines the static library mbfe_spatial_baselines, the trees of
# tests/reference/ for the libraries found, which carries MBFE_HAVE_MUJOCO and
# MBFE_HAVE_RBDL to whoever links it; no such target when neither is found.
set(MBFE_RBDL_DIR "" CACHE PATH "Install prefix of RBDL to compare the spatial kernels with (optional)")

set(mbfe_baseline_sources "")
# The header and the library, not Debian's CMake package of MuJoCo 2.2.2: it
# names /usr/include/libqhull_r/ among its include folders, which only
# libqhull-dev provides, and CMake refuses an imported target with a missing one.
find_path(MBFE_MUJOCO_INCLUDE_DIR mujoco/mujoco.h)
find_library(MBFE_MUJOCO_LIBRARY mujoco)
if(MBFE_MUJOCO_INCLUDE_DIR AND MBFE_MUJOCO_LIBRARY)
  set(mujoco_FOUND TRUE)
  list(APPEND mbfe_baseline_sources ${CMAKE_SOURCE_DIR}/tests/reference/mujoco_tree.cpp)
  message(STATUS "mbfe: MuJoCo found (${MBFE_MUJOCO_LIBRARY}): spatial kernels compared with it")
else()
  message(STATUS "mbfe: MuJoCo not found (Debian libmujoco-dev): no comparison of the spatial kernels with it")
endif()

find_path(MBFE_RBDL_INCLUDE_DIR rbdl/rbdl.h HINTS "${MBFE_RBDL_DIR}/include")
find_library(MBFE_RBDL_LIBRARY rbdl HINTS "${MBFE_RBDL_DIR}/lib")
if(MBFE_RBDL_INCLUDE_DIR AND MBFE_RBDL_LIBRARY)
  list(APPEND mbfe_baseline_sources ${CMAKE_SOURCE_DIR}/tests/reference/rbdl_tree.cpp)
  message(STATUS "mbfe: RBDL found (${MBFE_RBDL_LIBRARY}): spatial kernels compared with it")
else()
  message(STATUS "mbfe: RBDL not found: no comparison of the spatial kernels with it "
                 "(configure with -DMBFE_RBDL_DIR=<its install prefix>)")
endif()

if(mbfe_baseline_sources)
  add_library(mbfe_spatial_baselines STATIC ${mbfe_baseline_sources})
  target_include_directories(mbfe_spatial_baselines PUBLIC ${CMAKE_SOURCE_DIR})
  target_link_libraries(mbfe_spatial_baselines PUBLIC mbfe_ir Eigen3::Eigen)
  if(mujoco_FOUND)
    target_include_directories(mbfe_spatial_baselines SYSTEM PUBLIC ${MBFE_MUJOCO_INCLUDE_DIR})
    target_link_libraries(mbfe_spatial_baselines PUBLIC ${MBFE_MUJOCO_LIBRARY})
    target_compile_definitions(mbfe_spatial_baselines PUBLIC MBFE_HAVE_MUJOCO)
  endif()
  if(MBFE_RBDL_INCLUDE_DIR AND MBFE_RBDL_LIBRARY)
    target_include_directories(mbfe_spatial_baselines SYSTEM PUBLIC ${MBFE_RBDL_INCLUDE_DIR})
    target_link_libraries(mbfe_spatial_baselines PUBLIC ${MBFE_RBDL_LIBRARY})
    target_compile_definitions(mbfe_spatial_baselines PUBLIC MBFE_HAVE_RBDL)
  endif()
endif()
