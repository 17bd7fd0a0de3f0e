# tests/layers/no_relative_includes.cmake — fails when a library or program source includes a file by
# a relative path that leaves its folder ("../"), which would step around the layers' include roots.
file(GLOB_RECURSE sources ${ROOT}/dec/*.h ${ROOT}/dec/*.cpp ${ROOT}/operators/*.h ${ROOT}/operators/*.cpp
     ${ROOT}/apps/*.h ${ROOT}/apps/*.cpp ${ROOT}/python/src/*.cpp ${ROOT}/python/src/*.h)
set(bad "")
foreach(f ${sources})
  file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<][^\">]*\\.\\./")
  if(lines)
    list(APPEND bad "${f}: ${lines}")
  endif()
endforeach()
if(bad)
  string(REPLACE ";" "\n" bad "${bad}")
  message(FATAL_ERROR "relative includes across folders:\n${bad}")
endif()
list(LENGTH sources n)
message(STATUS "${n} sources, no relative include leaves its folder")
