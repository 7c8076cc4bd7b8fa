# mbfe_forbid_links(<target> <forbidden>...)
#
# Fails the configuration when <target> links, directly or through the
# libraries it links, any of <forbidden> (target names). Keeps the layering of
# docs/architecture.md true at build time: a program that only simulates links
# mbfe_runtime and must not drag in the YAML parser, OpenSSL or GiNaC.
function(_mbfe_collect_links target out_var)
  set(seen ${${out_var}})
  foreach(property LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
    get_target_property(links ${target} ${property})
    if(NOT links)
      continue()
    endif()
    foreach(link ${links})
      # $<LINK_ONLY:x> and other generator expressions around a name.
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" link "${link}")
      if(link IN_LIST seen)
        continue()
      endif()
      list(APPEND seen ${link})
      if(TARGET ${link})
        _mbfe_collect_links(${link} seen)
      endif()
    endforeach()
  endforeach()
  set(${out_var} ${seen} PARENT_SCOPE)
endfunction()

function(mbfe_forbid_links target)
  set(links "")
  _mbfe_collect_links(${target} links)
  foreach(forbidden ${ARGN})
    if(forbidden IN_LIST links)
      message(FATAL_ERROR "layering: ${target} links ${forbidden} (docs/architecture.md); it must not")
    endif()
  endforeach()
endfunction()
