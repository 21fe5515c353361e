# The library as an installable package. Both libraries are linked from the
# objects already built for vismap_core and vismap_io; what they need (GMP,
# MPFR, OpenMP, cairo) stays private to them: a user includes
# <vismap/vismap.h>, which names no CGAL, GMP or Boost type, and links
# vismap::vismap (shared) or vismap::vismap_static.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(VISMAP_PACKAGE_OBJECTS $<TARGET_OBJECTS:vismap_core> $<TARGET_OBJECTS:vismap_io>)
add_library(vismap_shared SHARED ${VISMAP_PACKAGE_OBJECTS})
add_library(vismap_static STATIC ${VISMAP_PACKAGE_OBJECTS})
foreach(lib vismap_shared vismap_static)
  target_include_directories(${lib} INTERFACE
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  # (A static library's private dependencies reach its users as link-only items:
  # plain library files, and OpenMP's target, which vismapConfig.cmake finds.)
  target_link_libraries(${lib} PRIVATE ${GMPXX_LIB} ${GMP_LIB} ${MPFR_LIB})
  if(OpenMP_CXX_FOUND)
    target_link_libraries(${lib} PRIVATE OpenMP::OpenMP_CXX)
  endif()
  if(CAIRO_FOUND)
    target_link_libraries(${lib} PRIVATE ${CAIRO_LINK_LIBRARIES})
  endif()
endforeach()
set_target_properties(vismap_shared PROPERTIES OUTPUT_NAME vismap EXPORT_NAME vismap
                      VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR})
set_target_properties(vismap_static PROPERTIES OUTPUT_NAME vismap EXPORT_NAME vismap_static)

install(TARGETS vismap_shared vismap_static EXPORT vismapTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(FILES ${PROJECT_SOURCE_DIR}/include/vismap/vismap.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vismap)
install(EXPORT vismapTargets NAMESPACE vismap:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/vismap)
set(VISMAP_WITH_OPENMP ${OpenMP_CXX_FOUND})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/vismapConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/vismapConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/vismap)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/vismapConfigVersion.cmake COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/vismapConfig.cmake ${PROJECT_BINARY_DIR}/vismapConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/vismap)
