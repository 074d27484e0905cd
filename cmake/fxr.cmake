# Helpers shared by the test and benchmark folders.

set(FXR_WARNINGS -Wall -Wextra -Wno-unused-parameter)

# fxr_add_test_dir(DIR LABEL LIBS...)
# Every DIR/*_test.cpp becomes one GoogleTest executable; its tests get ctest label LABEL,
# plus `slow` when the file name ends in _slow_test.cpp. Adding a test is adding a file.
function(fxr_add_test_dir dir label)
  file(GLOB srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/*_test.cpp)
  foreach(src IN LISTS srcs)
    get_filename_component(name ${src} NAME_WE)
    set(target ${label}_${name})
    add_executable(${target} ${src})
    target_compile_options(${target} PRIVATE ${FXR_WARNINGS})
    target_link_libraries(${target} PRIVATE ${ARGN} GTest::gtest GTest::gtest_main)
    set(labels ${label})
    if(name MATCHES "_slow_test$")
      list(APPEND labels slow)
    endif()
    gtest_discover_tests(${target}
      WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
      DISCOVERY_MODE PRE_TEST
      DISCOVERY_TIMEOUT 60
      PROPERTIES LABELS "${labels}" ENVIRONMENT "FXR_SOURCE_DIR=${CMAKE_SOURCE_DIR};FXR_BINARY_DIR=${CMAKE_BINARY_DIR}")
  endforeach()
endfunction()
