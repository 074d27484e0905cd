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
      DISCOVERY_TIMEOUT 60)
    # Labels and environment are set after discovery, not through PROPERTIES: CMake 3.25's
    # gtest_discover_tests flattens list values there (LABELS "model;slow" became LABELS model
    # plus a property named `slow`, and ENVIRONMENT lost its second entry). The discovered tests
    # are in the list ${target}_TESTS when ctest reads the include file below, which runs after
    # the discovery's own include (TEST_INCLUDE_FILES keeps the order).
    set(props ${CMAKE_CURRENT_BINARY_DIR}/${target}_properties.cmake)
    file(WRITE ${props}
      "if(DEFINED ${target}_TESTS)\n"
      "  set_tests_properties(\${${target}_TESTS} PROPERTIES LABELS \"${labels}\"\n"
      "    ENVIRONMENT \"FXR_SOURCE_DIR=${CMAKE_SOURCE_DIR};FXR_BINARY_DIR=${CMAKE_BINARY_DIR}\")\n"
      "endif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${props})
  endforeach()
endfunction()
