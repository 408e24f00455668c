# stiffsoft_library(NAME FOLDER) — one static library per part of the pipeline, from every .cpp
# below stiffsoft/FOLDER; exported (installed) as stiffsoft::NAME. Headers are included as
# <stiffsoft/FOLDER/...>, from the source tree in a build and from PREFIX/include once installed.
function(stiffsoft_library name folder)
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/stiffsoft/${folder}/*.cpp)
  add_library(stiffsoft_${name} STATIC ${sources})
  add_library(stiffsoft::${name} ALIAS stiffsoft_${name})
  set_target_properties(stiffsoft_${name} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(stiffsoft_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(stiffsoft_${name} PUBLIC cxx_std_20)
  target_compile_options(stiffsoft_${name} PRIVATE -Wall -Wextra)
  set_property(GLOBAL APPEND PROPERTY STIFFSOFT_EXPORTED_TARGETS stiffsoft_${name})
endfunction()
