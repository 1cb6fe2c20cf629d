# What `cmake --install` puts under share/rockhatch, and the Debian package (CPack):
#   cpack --config build/CPackConfig.cmake -B DIR    -> DIR/rockhatch_<version>_amd64.deb
# (docs/install.md). The libraries, the command, the Python package, the man page and the
# completion are installed by the CMakeLists.txt of their folders.

install(DIRECTORY ${PROJECT_SOURCE_DIR}/qgis_plugin/rockhatch_qgis DESTINATION ${RH_INSTALL_DATADIR}/qgis_plugin
        PATTERN __pycache__ EXCLUDE PATTERN "*.pyc" EXCLUDE)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/install_qgis_plugin.sh DESTINATION ${RH_INSTALL_DATADIR}/qgis_plugin)
file(GLOB RH_STYLE_SCRIPTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/styles/*.py)
install(FILES ${RH_STYLE_SCRIPTS} DESTINATION ${RH_INSTALL_DATADIR}/styles)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/sample_montblanc DESTINATION ${RH_INSTALL_DATADIR}/data)
# The web page of `rockhatch serve` (docs/web.md), with MapLibre GL JS's distribution from
# web/node_modules (scripts/setup.sh runs npm ci there; without it the page is installed
# alone and `rockhatch serve` says MapLibre is missing).
install(FILES ${PROJECT_SOURCE_DIR}/web/index.html ${PROJECT_SOURCE_DIR}/web/app.js ${PROJECT_SOURCE_DIR}/web/style.css
        DESTINATION ${RH_INSTALL_DATADIR}/web)
set(RH_MAPLIBRE_DIST ${PROJECT_SOURCE_DIR}/web/node_modules/maplibre-gl/dist)
install(FILES ${RH_MAPLIBRE_DIST}/maplibre-gl.js ${RH_MAPLIBRE_DIST}/maplibre-gl.css ${RH_MAPLIBRE_DIST}/LICENSE.txt
        DESTINATION ${RH_INSTALL_DATADIR}/web/node_modules/maplibre-gl/dist OPTIONAL)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME rockhatch)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "rockhatch maintainers <rockhatch@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "rock drawing for maps and programmable element textures")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
  "rockhatch draws rock hatching for maps from a DEM and a partition of the rock areas\n"
  "(GeoPackage, SVG and PNG outputs), with a Python module, a QGIS Processing provider and\n"
  "tiled runs on Dask. libtex, its engine, programs element textures on exact planar maps (CGAL).")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# The shared libraries' packages (GDAL, PROJ through GDAL, GeographicLib, GMP and MPFR for
# CGAL, tinyxml2, OpenImageIO, SQLite, jemalloc) come from dpkg-shlibdeps on the installed
# binaries; the Python side is declared: the compiled module is built for Debian's 3.11.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${PROJECT_BINARY_DIR}/libtex ${PROJECT_BINARY_DIR}/carto)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= 3.11), python3 (<< 3.12), python3-numpy")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-distributed, python3-dask, python3-gdal, python3-psutil, gdal-bin")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "qgis, python3-qgis, librsvg2-bin")
set(CPACK_STRIP_FILES ON)
include(CPack)
