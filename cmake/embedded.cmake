# The embedded profile (SR_EMBEDDED=ON, docs/portability.md): included by
# the top-level CMakeLists.txt after the core library, in place of
# everything that follows it there (softrast_io, the tool, install,
# examples, Python, bench).  The core is built with SR_EMBEDDED defined,
# which gives it one thread (SR_MAX_THREADS) and small primitive batches
# (SR_BATCH_DEFAULT), and so must every program that includes its header.
target_compile_definitions(softrast_objects PUBLIC SR_EMBEDDED=1)
target_compile_definitions(softrast_static INTERFACE SR_EMBEDDED=1)
target_compile_definitions(softrast INTERFACE SR_EMBEDDED=1)

if(NOT SR_BUILD_TESTS)
  return()
endif()
enable_testing()
# The tests that need neither softrast_io, nor the shared models, nor
# more than one thread.
set(SR_EMBEDDED_TESTS
  test_arena test_attribute test_bands test_bezier test_bin test_block test_clip
  test_clip_view test_depth test_draw2d_clip test_draw2d_curves test_draw2d_fill
  test_draw2d_fill_cells test_draw2d_gouraud_incremental test_draw2d_paint_row
  test_draw2d_region test_draw2d_shapes test_draw_coverage test_interp test_light_lanes
  test_lines test_lines3d test_math test_newell test_resample
  test_stencil test_texture test_vertex_wide test_zero_desc)
set(SR_TESTS_DIR ${CMAKE_CURRENT_SOURCE_DIR}/tests)
add_library(sr_test_harness STATIC ${SR_TESTS_DIR}/sr_test.c)
target_include_directories(sr_test_harness PUBLIC ${SR_TESTS_DIR}
  ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR}/include)
target_compile_definitions(sr_test_harness PUBLIC
  SR_SHARED_MODELS_DIR="${PROJECT_SOURCE_DIR}/../shared/models"
  SR_TEST_OUT_DIR="${CMAKE_CURRENT_BINARY_DIR}/tests/out"
  SR_TEST_SRC_DIR="${SR_TESTS_DIR}")
target_link_libraries(sr_test_harness PUBLIC softrast_static)
foreach(name ${SR_EMBEDDED_TESTS})
  add_executable(${name} ${SR_TESTS_DIR}/${name}.c)
  target_link_libraries(${name} PRIVATE sr_test_harness)
  add_test(NAME ${name} COMMAND ${name})
  set_tests_properties(${name} PROPERTIES TIMEOUT 3600)
endforeach()
