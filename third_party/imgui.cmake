# Glue for what Debian lacks: a CMake target around the system Dear ImGui (libimgui-dev 1.86).
#
# Debian ships the headers (/usr/include/imgui), the core as libimgui.a (pkg-config imgui) and the platform
# and renderer backends only as sources under /usr/share/doc/libimgui-dev/examples/backends/. The target
# `impactlab::imgui` compiles the GLFW and OpenGL 3 backends as they are (-w on those two files only: they
# are not ours) and links libimgui, stb, GLFW and OpenGL.
# Included from app/gui/CMakeLists.txt: include(${PROJECT_SOURCE_DIR}/third_party/imgui.cmake).
include_guard(GLOBAL)

find_package(PkgConfig REQUIRED)
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
pkg_check_modules(GLFW3 REQUIRED IMPORTED_TARGET glfw3)
set(OpenGL_GL_PREFERENCE GLVND)
find_package(OpenGL REQUIRED)

set(IMPACTLAB_IMGUI_BACKEND_DIR /usr/share/doc/libimgui-dev/examples/backends
    CACHE PATH "Folder with imgui_impl_glfw.cpp and imgui_impl_opengl3.cpp (Debian libimgui-dev)")
foreach(f imgui_impl_glfw.cpp imgui_impl_opengl3.cpp)
  if(NOT EXISTS ${IMPACTLAB_IMGUI_BACKEND_DIR}/${f})
    message(FATAL_ERROR "impactlab-gui: ${IMPACTLAB_IMGUI_BACKEND_DIR}/${f} not found (install libimgui-dev, "
                        "or set IMPACTLAB_IMGUI_BACKEND_DIR, or configure with -DIMPACTLAB_BUILD_APP=OFF)")
  endif()
endforeach()

add_library(impactlab_imgui STATIC
  ${IMPACTLAB_IMGUI_BACKEND_DIR}/imgui_impl_glfw.cpp
  ${IMPACTLAB_IMGUI_BACKEND_DIR}/imgui_impl_opengl3.cpp)
add_library(impactlab::imgui ALIAS impactlab_imgui)
# The backends are third-party code compiled unmodified: silence their warnings, and only theirs.
set_source_files_properties(
  ${IMPACTLAB_IMGUI_BACKEND_DIR}/imgui_impl_glfw.cpp
  ${IMPACTLAB_IMGUI_BACKEND_DIR}/imgui_impl_opengl3.cpp
  PROPERTIES COMPILE_OPTIONS "-w")
# SYSTEM: warnings from ImGui's own headers do not count against the files that include them.
target_include_directories(impactlab_imgui SYSTEM PUBLIC /usr/include/imgui /usr/include/imgui/backends)
target_link_libraries(impactlab_imgui PUBLIC PkgConfig::IMGUI PkgConfig::STB PkgConfig::GLFW3 OpenGL::GL)
if(IMPACTLAB_SANITIZE)
  # Keep the sanitizer's runtime consistent across the whole program.
  target_compile_options(impactlab_imgui PRIVATE -fsanitize=${IMPACTLAB_SANITIZE})
endif()
