# The estimators never depend on chaos::models: no file under chaos/src or chaos/include/chaos may
# include a models header, public (<chaos/models/...>, or any path through a models/ directory) or
# private (the file names in chaos/models/src), and the models headers may not sit in the
# estimators' include root. Run as the ctest test models.boundary:
#   cmake -DSOURCE_DIR=<repository root> -P tests/check_models_boundary.cmake
if(NOT DEFINED SOURCE_DIR)
  message(FATAL_ERROR "check_models_boundary.cmake: pass -DSOURCE_DIR=<repository root>")
endif()

set(problems "")
if(IS_DIRECTORY "${SOURCE_DIR}/chaos/include/chaos/models")
  string(APPEND problems "  chaos/include/chaos/models/ exists: models headers belong in chaos/models/include/chaos/models/\n")
endif()

# The private models headers, by file name (zoo_model.hpp, zoo_table.inc from zoo_table.inc.in, ...).
file(GLOB private_headers RELATIVE "${SOURCE_DIR}/chaos/models/src"
     "${SOURCE_DIR}/chaos/models/src/*.hpp" "${SOURCE_DIR}/chaos/models/src/*.inc.in")
set(private_names "")
foreach(name ${private_headers})
  string(REGEX REPLACE "\\.in$" "" name "${name}")
  string(REGEX REPLACE "([.+])" "\\\\\\1" name "${name}")
  list(APPEND private_names "${name}")
endforeach()
list(JOIN private_names "|" private_alternatives)
set(path_pattern "([^\">]*/)?models/[^\">]*")
if(private_alternatives)
  string(APPEND path_pattern "|([^\">]*/)?(${private_alternatives})")
endif()
set(include_pattern "^[ \t]*#[ \t]*include[ \t]*[<\"](${path_pattern})[\">]")

file(GLOB_RECURSE estimator_files LIST_DIRECTORIES false
     "${SOURCE_DIR}/chaos/src/*" "${SOURCE_DIR}/chaos/include/chaos/*")
set(checked 0)
foreach(path ${estimator_files})
  math(EXPR checked "${checked} + 1")
  file(STRINGS "${path}" hits REGEX "${include_pattern}")
  file(RELATIVE_PATH shown "${SOURCE_DIR}" "${path}")
  foreach(line ${hits})
    string(STRIP "${line}" line)
    string(APPEND problems "  ${shown}: ${line}\n")
  endforeach()
endforeach()

if(checked EQUAL 0)
  message(FATAL_ERROR "models boundary: no estimator files found under ${SOURCE_DIR}/chaos/src or chaos/include/chaos")
endif()
if(NOT problems STREQUAL "")
  message(FATAL_ERROR "models boundary: the estimator library (chaos/src, chaos/include/chaos) must not "
                      "include chaos::models headers; move the code into chaos/models or drop the include:\n"
                      "${problems}")
endif()
message(STATUS "models boundary: ${checked} estimator files, none includes a models header")
