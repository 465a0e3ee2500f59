# trigrav_add_library(<component> SOURCES <files...> [PUBLIC <targets...>] [PRIVATE <targets...>])
#
# One trigrav component library: target trigrav_<component> with alias and export name
# trigrav::<component>, C++17, public headers in <current folder>/include (installed as is),
# warnings for its own sources only. Static or shared after BUILD_SHARED_LIBS; always position
# independent, so that a static install links into a user's shared object or Python extension.
function(trigrav_add_library component)
  cmake_parse_arguments(arg "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  set(target trigrav_${component})
  add_library(${target} ${arg_SOURCES})
  add_library(trigrav::${component} ALIAS ${target})
  set_target_properties(${target} PROPERTIES
    EXPORT_NAME ${component}
    POSITION_INDEPENDENT_CODE ON
    VERSION ${PROJECT_VERSION}
    SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
    INSTALL_RPATH "$ORIGIN")  # shared: the components find each other where they are installed
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target}
    PUBLIC ${arg_PUBLIC}
    PRIVATE ${arg_PRIVATE} $<BUILD_INTERFACE:trigrav_warnings>)
  install(TARGETS ${target} EXPORT trigravTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY include/trigrav DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
