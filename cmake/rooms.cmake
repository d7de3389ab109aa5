# Rooms: folders of one role each, whose includes point down only.
#
# tessera_room(NAME [DIR dir] [DEPENDS rooms...] [SOURCES files...] [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
#   A room of code built once per build of the renderer (tessera_renderer_builds: the generic
#   instruction set and, on x86-64, x86-64-v3): a static library tessera_<NAME><suffix> that
#   links the rooms it DEPENDS on, or an interface library when it has no SOURCES. DIR
#   defaults to renderer/<NAME>.
# tessera_once_room(NAME DIR dir [DEPENDS rooms...] [SOURCES files...] [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
#   A room compiled once (app, scene_io, denoiser): tessera_<NAME>. A program that links it
#   links the build of each per-build room it DEPENDS on that the program's
#   TESSERA_RENDERER_SUFFIX property names (none: the generic build).
# tessera_check_rooms()
#   After every room: a target of the default build that fails when a file includes a header
#   of a room that is neither its own nor below it (DEPENDS, followed through).

set_property(GLOBAL PROPERTY tessera_rooms "")

function(tessera_record_room name dir depends)
  set_property(GLOBAL APPEND PROPERTY tessera_rooms ${name})
  set_property(GLOBAL PROPERTY tessera_room_${name}_dir ${dir})
  set_property(GLOBAL PROPERTY tessera_room_${name}_depends "${depends}")
  foreach(dep IN LISTS depends)
    get_property(known GLOBAL PROPERTY tessera_room_${dep}_dir SET)
    if(NOT known)
      message(FATAL_ERROR "room ${name}: ${dep} is not a room defined before it (rooms depend on rooms below them)")
    endif()
  endforeach()
endfunction()

function(tessera_room name)
  cmake_parse_arguments(R "" "DIR" "DEPENDS;SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  if(NOT R_DIR)
    set(R_DIR renderer/${name})
  endif()
  tessera_record_room(${name} ${R_DIR} "${R_DEPENDS}")
  set_property(GLOBAL PROPERTY tessera_room_${name}_per_build ON)
  foreach(build IN LISTS tessera_renderer_builds)
    set(suffix ${tessera_build_${build}_suffix})
    set(target tessera_${name}${suffix})
    set(deps "")
    foreach(dep IN LISTS R_DEPENDS)
      list(APPEND deps tessera_${dep}${suffix})
    endforeach()
    if(R_SOURCES)
      add_library(${target} STATIC ${R_SOURCES})
      target_compile_options(${target} PRIVATE ${tessera_build_${build}_options})
      target_include_directories(${target} PRIVATE ${tessera_tables_dir})
      target_compile_definitions(${target} PRIVATE TESSERA_VERSION="${PROJECT_VERSION}"
                                 TESSERA_ISA="${tessera_build_${build}_isa}" TESSERA_MODULE_DIR="${PROJECT_BINARY_DIR}")
      target_link_libraries(${target} PUBLIC tessera_room_base ${deps} ${R_PUBLIC_LIBS}
                            PRIVATE fmt::fmt ${R_PRIVATE_LIBS})
    else()
      add_library(${target} INTERFACE)
      target_link_libraries(${target} INTERFACE tessera_room_base ${deps} ${R_PUBLIC_LIBS})
    endif()
  endforeach()
endfunction()

function(tessera_once_room name)
  cmake_parse_arguments(R "" "DIR" "DEPENDS;SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  tessera_record_room(${name} ${R_DIR} "${R_DEPENDS}")
  set(deps "")
  foreach(dep IN LISTS R_DEPENDS)
    get_property(per_build GLOBAL PROPERTY tessera_room_${dep}_per_build)
    if(per_build)
      # The build the linking program or test chooses (its TESSERA_RENDERER_SUFFIX property;
      # none: the generic build).
      list(APPEND deps tessera_${dep}$<TARGET_PROPERTY:TESSERA_RENDERER_SUFFIX>)
    else()
      list(APPEND deps tessera_${dep})
    endif()
  endforeach()
  add_library(tessera_${name} STATIC ${R_SOURCES})
  target_link_libraries(tessera_${name} PUBLIC tessera_room_base ${deps} ${R_PUBLIC_LIBS} PRIVATE ${R_PRIVATE_LIBS})
endfunction()

# A room's own dependencies and theirs, in order.
function(tessera_room_closure name out)
  set(result "")
  get_property(direct GLOBAL PROPERTY tessera_room_${name}_depends)
  foreach(dep IN LISTS direct)
    tessera_room_closure(${dep} below)
    list(APPEND result ${dep} ${below})
  endforeach()
  list(REMOVE_DUPLICATES result)
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

function(tessera_check_rooms)
  get_property(rooms GLOBAL PROPERTY tessera_rooms)
  set(text "")
  foreach(room IN LISTS rooms)
    get_property(dir GLOBAL PROPERTY tessera_room_${room}_dir)
    tessera_room_closure(${room} below)
    set(dirs "")
    foreach(dep IN LISTS below)
      get_property(dep_dir GLOBAL PROPERTY tessera_room_${dep}_dir)
      list(APPEND dirs ${dep_dir})
    endforeach()
    string(APPEND text "${dir}=${dirs}\n")
  endforeach()
  set(rooms_file ${PROJECT_BINARY_DIR}/rooms.txt)
  file(WRITE ${rooms_file} "${text}")
  add_custom_target(tessera_check_rooms ALL
    COMMAND ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR} -DROOMS=${rooms_file} -P ${PROJECT_SOURCE_DIR}/cmake/check_rooms.cmake
    COMMENT "Checking that includes point down the rooms" VERBATIM)
endfunction()
