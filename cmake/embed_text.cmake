# Embed a text file into C as a NUL-terminated unsigned char array.
#   cmake -DIN=<file> -DOUT=<file.c> -DSYMBOL=<name> -P embed_text.cmake
# Used at build time for files that are themselves build outputs (the
# devices' generated EDS files), so the daemon carries them without reading
# the build tree at run time.
if(NOT IN OR NOT OUT OR NOT SYMBOL)
  message(FATAL_ERROR "embed_text.cmake: IN, OUT and SYMBOL are required")
endif()
file(READ "${IN}" hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
string(REGEX REPLACE "((0x[0-9a-f][0-9a-f],){16})" "\\1\n    " bytes "${bytes}")
get_filename_component(name "${IN}" NAME)
file(WRITE "${OUT}.tmp"
  "/* ${name}, embedded by cmake/embed_text.cmake. Do not edit. */\n"
  "extern const unsigned char ${SYMBOL}[];\n"
  "const unsigned char ${SYMBOL}[] = {\n    ${bytes}0x00};\n")
file(RENAME "${OUT}.tmp" "${OUT}")
