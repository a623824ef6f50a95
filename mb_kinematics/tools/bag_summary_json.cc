#include "mb_kinematics/tools/bag_summary_json.h"

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "mb_kinematics/io/number_format.h"
#include "mb_kinematics/io/report.h"
#include "mb_kinematics/tools/error_bar_summary.h"
#include "mb_kinematics/offline/output_file.h"
#include "mb_kinematics/tools/bag_cli.h"

namespace mbk_offline {
namespace {

std::string number(double x) { return std::isfinite(x) ? mbk::format_double(x) : "null"; }

std::string outputs(const BagOutputs& o) {
  std::string text = "[";
  for (const NamedFile& file : output_files(o))
    text += (text.size() > 1 ? ", " : "") + mbk::json_string(file.path);
  return text + "]";
}

std::string drops(const mbk::DropLog& log) {
  std::string text = "{";
  for (const auto& d : log.drops)
    text +=
        (text.size() > 1 ? ", " : "") + mbk::json_string(d.first) + ": " + std::to_string(d.second);
  return text + "}";
}

std::string object(const BagOptions& o, const std::string& status, const BagSummary& s,
                   const std::string& error) {
  const double noise = s.errors.empty() ? NAN : mbk::median_noise(s.errors);
  return "{\"input\": " + mbk::json_string(o.input) + ", \"outputs\": " + outputs(o) +
         ", \"status\": \"" + status + "\", \"read\": " + std::to_string(s.read) +
         ", \"written\": " + std::to_string(s.written) +
         ", \"dropped\": " + std::to_string(s.log.dropped()) + ", \"drops\": " + drops(s.log) +
         ", \"unreadable\": " + std::to_string(s.unreadable) +
         ", \"estimator\": " + mbk::json_string(s.estimator) +
         ", \"noise_level\": " + number(noise) + ", \"max_gap\": " + number(s.max_gap) +
         ", \"seconds\": " + number(s.wall_seconds) + ", \"error\": " + mbk::json_string(error) +
         "}\n";
}

// Why a finished run is partial, in the words of the printed summary; "" when it is not.
std::string partial_reason(const BagSummary& s) {
  if (s.unreadable > 0)
    return "unreadable " + std::to_string(s.unreadable) +
           " messages, skipped: the output is partial (first: " + s.unreadable_example + ")";
  return s.written == 0 ? "nothing written" : "";
}

}  // namespace

std::string format_summary_json(const BagOptions& options, const BagSummary& summary) {
  return object(options, exit_status(summary) == 0 ? "ok" : "partial", summary,
                partial_reason(summary));
}

std::string format_failure_json(const BagOptions& options, const std::string& error) {
  return object(options, "failed", BagSummary{}, error);
}

void write_summary_json(const std::string& path, const std::string& text) {
  OutputFile file(path);
  {
    std::ofstream out(file.writing(), std::ios::binary | std::ios::trunc);
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write " + path);
  }
  file.commit();
}

}  // namespace mbk_offline
