# dewall_warnings(target): the warning set for the project's own targets.
function(dewall_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wno-maybe-uninitialized)
endfunction()
