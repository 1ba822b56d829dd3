// The output folder of a case command (see case_output.h).
#include "config/case_output.h"

#include "base/output_files.h"
#include "base/user_error.h"

namespace occlude::app {

std::filesystem::path OutputFolder(const CaseConfig& config, const std::string& out_option) {
  if (!out_option.empty()) return out_option;
  if (config.output_dir) return *config.output_dir;
  throw UserError(config.file.string() +
                  ": no output folder; set [output] folder = \"...\" or pass --out");
}

std::filesystem::path PrepareCaseOutput(const CaseConfig& config, const std::string& out_option) {
  const std::filesystem::path out = OutputFolder(config, out_option);
  try {
    PrepareOutputDir(out);
  } catch (const UserError& e) {
    if (!out_option.empty()) throw;
    throw UserError(config.file.string() + ": output.folder: " + e.what());
  }
  return out;
}

}  // namespace occlude::app
