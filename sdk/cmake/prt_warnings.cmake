# prt_set_warnings(<target>): -Wall -Wextra (and -Werror with PRT_WERROR) on first-party code only.
function(prt_set_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<OR:$<COMPILE_LANG_AND_ID:CXX,GNU,Clang>,$<COMPILE_LANG_AND_ID:C,GNU,Clang>>:-Wall -Wextra>
    $<$<BOOL:${PRT_WERROR}>:-Werror>)
endfunction()
