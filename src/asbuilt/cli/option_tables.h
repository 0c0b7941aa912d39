#ifndef ASBUILT_CLI_OPTION_TABLES_H_
#define ASBUILT_CLI_OPTION_TABLES_H_

// Every Options struct that has a field list (util/fields.h), with the flags
// that set it: what `asbuilt help options` prints and what the option tables
// in docs/ are generated from (cli/docs_test: `<!-- options NAME -->` …
// `<!-- /options -->` blocks; ASBUILT_UPDATE_DOCS=1 rewrites them).

#include <string>
#include <string_view>
#include <vector>

#include "asbuilt/util/fields.h"

namespace asbuilt::cli {

struct OptionTable {
  std::string_view name;    // The struct: "PlanOptions".
  std::string_view header;  // Where it is declared: "plan/plan_options.h".
  std::string_view flags;   // Which commands take it, and how: "`asbuilt plan --NAME`, …".
  std::vector<Field> fields;
};

// In the order the pipeline uses them (scene → render → train → survey).
const std::vector<OptionTable>& OptionTables();

// One table as Markdown: a line naming the header and the flags, then the
// fields (name, type and bounds, default, description). Throws
// InvalidArgument naming the known structs for an unknown `name`.
std::string OptionTableMarkdown(std::string_view name);

}  // namespace asbuilt::cli

#endif  // ASBUILT_CLI_OPTION_TABLES_H_
