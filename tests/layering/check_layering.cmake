# The include rules, checked on every source file (ctest: layering). Run as
#   cmake -DROOT=<repo> -P check_layering.cmake
# Rules:
#   - engine/ includes no UI or app header, no SDL, ImGui or GL;
#   - Box2D (<box2d/...>) is included only under engine/dynamics/ and tests/engine/dynamics/;
#   - ui/ includes no app/ header;
#   - an engine folder includes only the engine folders it links (engine/CMakeLists.txt).
cmake_minimum_required(VERSION 3.22)

# Which engine folders each engine folder may include (itself and what it links, transitively).
set(allowed_core core)
set(allowed_model core model)
set(allowed_cable core model cable)
set(allowed_dynamics core model cable dynamics)
set(allowed_statics core statics)
set(allowed_membrane core membrane)
set(allowed_hand core model cable dynamics statics hand)
set(allowed_scenes core model cable dynamics statics hand scenes)
set(allowed_mujoco core model mujoco)

set(violations "")
file(GLOB_RECURSE sources RELATIVE ${ROOT} ${ROOT}/engine/*.h ${ROOT}/engine/*.cpp ${ROOT}/ui/*.h
     ${ROOT}/ui/*.cpp ${ROOT}/app/*.h ${ROOT}/app/*.cpp ${ROOT}/tests/*.h ${ROOT}/tests/*.cpp
     ${ROOT}/python/*.cpp ${ROOT}/python/*.h)
list(FILTER sources EXCLUDE REGEX "^tests/layering/")  # broken on purpose (the check's own test)
foreach(file ${sources})
  file(STRINGS ${ROOT}/${file} includes REGEX "^[ \t]*#[ \t]*include")
  foreach(line ${includes})
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]+)[>\"].*$" "\\1" header "${line}")
    if(header MATCHES "^box2d/" AND NOT file MATCHES "^(engine|tests/engine)/dynamics/")
      list(APPEND violations "${file}: includes <${header}>: Box2D belongs to engine/dynamics/ only")
    endif()
    if(file MATCHES "^engine/")
      if(header MATCHES "^(ui|app)/" OR header MATCHES "^(SDL|imgui|GL/|backends/)")
        list(APPEND violations "${file}: includes ${header}: the engine never includes UI or app code")
      endif()
      string(REGEX REPLACE "^engine/([^/]+)/.*$" "\\1" folder "${file}")
      if(header MATCHES "^engine/([^/]+)/" AND DEFINED allowed_${folder})
        string(REGEX REPLACE "^engine/([^/]+)/.*$" "\\1" target "${header}")
        list(FIND allowed_${folder} ${target} found)
        if(found EQUAL -1)
          list(APPEND violations "${file}: includes ${header}: engine/${folder} does not link engine/${target}")
        endif()
      endif()
    endif()
    if(file MATCHES "^ui/" AND header MATCHES "^app/")
      list(APPEND violations "${file}: includes ${header}: ui/ never includes app/")
    endif()
  endforeach()
endforeach()

list(LENGTH sources checked)
if(violations)
  foreach(v ${violations})
    message("${v}")  # one unwrapped line each
  endforeach()
  list(LENGTH violations broken)
  message(FATAL_ERROR "layering: ${checked} files checked, ${broken} broken rules")
endif()
message(STATUS "layering: ${checked} files checked, 0 broken rules")
