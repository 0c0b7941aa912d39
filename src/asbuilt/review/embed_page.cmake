# Writes OUT (a .cc file) defining asbuilt::kReviewPageHtml as the text of IN
# (review/page.html): the page's HTML, scripts and styles are compiled into
# the binary, so the review works offline (no CDN, no files to install).
file(READ "${IN}" page)
file(WRITE "${OUT}.tmp"
  "// Generated from review/page.html by review/embed_page.cmake; do not edit.\n"
  "namespace asbuilt {\nextern const char kReviewPageHtml[];\n"
  "const char kReviewPageHtml[] = R\"asbuilt_page(${page})asbuilt_page\";\n}  // namespace asbuilt\n")
file(RENAME "${OUT}.tmp" "${OUT}")
