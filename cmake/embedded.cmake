# The embedded profile (SR_EMBEDDED=ON, docs/portability.md): included by
# the top-level CMakeLists.txt after the core library, in place of
# everything that follows it there (softrast_io, the tool, install,
# examples, Python, bench).  The core is built with SR_EMBEDDED defined,
# which gives it one thread (SR_MAX_THREADS) and small primitive batches
# (SR_BATCH_DEFAULT), and so must every program that includes its header.
target_compile_definitions(softrast_objects PUBLIC SR_EMBEDDED=1)
target_compile_definitions(softrast_static INTERFACE SR_EMBEDDED=1)
target_compile_definitions(softrast INTERFACE SR_EMBEDDED=1)

if(SR_BUILD_TESTS)
  enable_testing()
  add_subdirectory(tests)
endif()
