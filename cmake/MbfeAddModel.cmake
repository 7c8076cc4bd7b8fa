# mbfe_add_model(<target> <model.yaml>)
#
# Generates the solver of a model description file at build time (with
# `mbfe generate`) and compiles it into the static library <target>. The
# library carries the ABI header, so a downstream project can call
#   extern "C" const mbfe_model_v1* mbfe_model_<model name>(void);
# and hand it to the runtime (mbfe::mbfe_runtime) or use the kernels directly.
# The model is regenerated whenever the model file or the generator changes.
function(mbfe_add_model target model_file)
  get_filename_component(model_path "${model_file}" ABSOLUTE)
  if(NOT EXISTS "${model_path}")
    message(FATAL_ERROR "mbfe_add_model(${target}): no such model file: ${model_file}")
  endif()
  # The output names follow the model's identifier (`model: <name>`); the
  # generator itself validates the whole file at build time.
  file(STRINGS "${model_path}" model_line REGEX "^model:[ \t]*[A-Za-z_][A-Za-z0-9_]*")
  string(REGEX REPLACE "^model:[ \t]*([A-Za-z_][A-Za-z0-9_]*).*" "\\1" model_name "${model_line}")
  if(NOT model_name)
    message(FATAL_ERROR "mbfe_add_model(${target}): ${model_file} has no top-level 'model: <identifier>' line")
  endif()
  if(TARGET mbfe_cli)
    set(generator $<TARGET_FILE:mbfe_cli>)
    set(generator_target mbfe_cli)
  elseif(TARGET mbfe::mbfe_cli)
    set(generator $<TARGET_FILE:mbfe::mbfe_cli>)
    set(generator_target mbfe::mbfe_cli)
  else()
    message(FATAL_ERROR "mbfe_add_model: neither target mbfe_cli nor mbfe::mbfe_cli exists (find_package(mbfe) first)")
  endif()
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/mbfe_generated/${target}")
  add_custom_command(
    OUTPUT "${out_dir}/${model_name}.h" "${out_dir}/${model_name}.cpp"
    COMMAND ${generator} generate "${model_path}" -o "${out_dir}" --quiet
    DEPENDS "${model_path}" ${generator_target}
    COMMENT "mbfe: generating the solver of ${model_file}"
    VERBATIM)
  add_library(${target} STATIC "${out_dir}/${model_name}.cpp" "${out_dir}/${model_name}.h")
  target_include_directories(${target} PUBLIC "${out_dir}")
  if(TARGET mbfe_abi)
    target_link_libraries(${target} PUBLIC mbfe_abi)
  else()
    target_link_libraries(${target} PUBLIC mbfe::mbfe_abi)
  endif()
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()
