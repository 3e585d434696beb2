# cmake --install and cpack -G DEB (included by the top-level CMakeLists.txt).
#
#   PREFIX/bin/impactlab, PREFIX/bin/impactlab-gui
#   PREFIX/share/impactlab/fonts/    the font both programs draw text with (found at run time from the
#                                    program's location: asset_path, app/common/program_assets.hpp)
#   PREFIX/share/impactlab/icons/    the window icon (likewise)
#   PREFIX/share/impactlab/shaders/  the GLSL sources of the shaders (impactlab-gui carries them compiled in)
#   PREFIX/share/applications/io.github.impactlab.impactlab.desktop, PREFIX/share/icons/hicolor/64x64/apps/impactlab.png,
#   PREFIX/share/metainfo/io.github.impactlab.impactlab.metainfo.xml
#
# The paths under share/ are fixed ("share", not CMAKE_INSTALL_DATADIR): asset_path looks for
# <program>/../share/impactlab.
install(TARGETS impactlab RUNTIME DESTINATION bin)
if(TARGET impactlab-gui)
  install(TARGETS impactlab-gui RUNTIME DESTINATION bin)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/io.github.impactlab.impactlab.desktop DESTINATION share/applications)
  install(FILES ${PROJECT_SOURCE_DIR}/packaging/io.github.impactlab.impactlab.metainfo.xml DESTINATION share/metainfo)
  install(FILES ${IMPACTLAB_ASSET_DIR}/icons/impactlab-64.png DESTINATION share/icons/hicolor/64x64/apps
          RENAME impactlab.png)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/ DESTINATION share/impactlab/shaders)
endif()
install(FILES ${IMPACTLAB_ASSET_DIR}/fonts/DejaVuSans.ttf ${IMPACTLAB_ASSET_DIR}/fonts/DejaVu-LICENSE.txt
        DESTINATION share/impactlab/fonts)
install(FILES ${IMPACTLAB_ASSET_DIR}/icons/impactlab-64.png DESTINATION share/impactlab/icons)

# The .deb: its dependencies are the Debian packages of the shared libraries the programs link
# (dpkg-shlibdeps), installed under /usr.
set(CPACK_PACKAGE_NAME impactlab)
set(CPACK_PACKAGE_VENDOR "impactlab")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Simulator and visualiser of a forced impact oscillator")
set(CPACK_PACKAGE_CONTACT "impactlab maintainers <impactlab@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_STRIP_FILES ON)
include(CPack)
