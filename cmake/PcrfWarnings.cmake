# Project code builds with warnings as errors; dependencies' headers are SYSTEM includes.
# -Wno-restrict: GCC 12's -Wrestrict reports false positives inside libstdc++'s
# std::string concatenation at -O2 (GCC bug 105329); it is not about our code.
function(pcrf_set_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
                              -Wno-restrict -Werror>)
endfunction()
