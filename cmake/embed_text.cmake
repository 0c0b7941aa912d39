# Writes OUT (a .cc file) defining `const char asbuilt::NAME[]` as the text of
# IN: what the binary must carry rather than install (the review pages, with
# their scripts and styles, so the review works offline; the Slurm batch
# scripts of scripts/slurm/, so `asbuilt cluster` writes the files a user can
# also sbatch by hand).
#   cmake -DIN=page.html -DOUT=page.cc -DNAME=kReviewPageHtml -P embed_text.cmake
if(NOT NAME)
  message(FATAL_ERROR "embed_text.cmake: give -DNAME")
endif()
file(READ "${IN}" text)
file(WRITE "${OUT}.tmp"
  "// Generated from ${IN} by cmake/embed_text.cmake; do not edit.\n"
  "namespace asbuilt {\nextern const char ${NAME}[];\n"
  "const char ${NAME}[] = R\"asbuilt_text(${text})asbuilt_text\";\n}  // namespace asbuilt\n")
file(RENAME "${OUT}.tmp" "${OUT}")
