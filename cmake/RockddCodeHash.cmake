# rockdd_code_hash(SOURCE DEFINITION): compiles SOURCE (in the current directory) with
# DEFINITION="<SHA-256 of every .cpp and .hpp of the current directory>", and re-runs
# configure when any of them changes. Caches keyed by it (meshes, orderings) then never read
# an entry that other code made.
function(rockdd_code_hash source definition)
  file(GLOB code CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp
       ${CMAKE_CURRENT_SOURCE_DIR}/*.hpp)
  list(SORT code)
  set(text "")
  foreach(file ${code})
    file(READ ${file} content)
    string(APPEND text "${content}")
  endforeach()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${code})
  string(SHA256 hash "${text}")
  set_property(SOURCE ${source} APPEND PROPERTY COMPILE_DEFINITIONS ${definition}="${hash}")
endfunction()
