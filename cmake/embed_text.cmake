# Writes a C++ header OUT holding the text of IN as `inline constexpr char NAME[]`, a raw
# string literal: static assets built into the binary (the preview's page).
#   cmake -D IN=file -D OUT=header -D NAME=kName -P embed_text.cmake
file(READ ${IN} text)
string(FIND "${text}" ")dermis_embed\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} holds the raw string's delimiter )dermis_embed\"")
endif()
file(WRITE ${OUT}.tmp "// Generated from ${IN} by cmake/embed_text.cmake; do not edit.\n#pragma once\n\n"
  "inline constexpr char ${NAME}[] = R\"dermis_embed(${text})dermis_embed\";\n")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
