# Writes OUT (a .cc file) defining asbuilt::NAME (default kReviewPageHtml) as
# the text of IN (review/page.html, review/home_page.html): the page's HTML, scripts and styles are compiled into
# the binary, so the review works offline (no CDN, no files to install).
if(NOT NAME)
  set(NAME kReviewPageHtml)
endif()
file(READ "${IN}" page)
file(WRITE "${OUT}.tmp"
  "// Generated from ${IN} by review/embed_page.cmake; do not edit.\n"
  "namespace asbuilt {\nextern const char ${NAME}[];\n"
  "const char ${NAME}[] = R\"asbuilt_page(${page})asbuilt_page\";\n}  // namespace asbuilt\n")
file(RENAME "${OUT}.tmp" "${OUT}")
