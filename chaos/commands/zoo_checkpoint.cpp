// zoo --checkpoint: the file of finished cases (zoo_checkpoint.hpp).

#include "zoo_checkpoint.hpp"

#include <dlfcn.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <vector>

#include "chaos/error.hpp"

namespace chaos::cli {

namespace {

constexpr int checkpoint_format = 3;

// A double as JSON: a number when finite (nlohmann writes the shortest text that reads back to the
// same double), else "inf", "-inf" or "nan", which JSON numbers cannot hold.
nlohmann::ordered_json real_json(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf";
}

double real_from_json(const nlohmann::ordered_json& j) {
  if (j.is_number()) return j.get<double>();
  const std::string s = j.get<std::string>();
  if (s == "inf") return std::numeric_limits<double>::infinity();
  if (s == "-inf") return -std::numeric_limits<double>::infinity();
  if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
  throw std::invalid_argument("not a number: " + s);
}

ZooVerdict verdict_from_string(const std::string& s) {
  for (const ZooVerdict v : {ZooVerdict::in_band, ZooVerdict::wrong, ZooVerdict::unsure})
    if (s == to_string(v)) return v;
  throw std::invalid_argument("not a verdict: " + s);
}

nlohmann::ordered_json estimate_to_json(const ZooEstimate& e) {
  nlohmann::ordered_json j;
  j["value"] = e.value ? real_json(*e.value) : nlohmann::ordered_json(nullptr);
  j["interval"] = e.interval ? nlohmann::ordered_json::array({real_json(e.interval->low), real_json(e.interval->high)})
                             : nlohmann::ordered_json(nullptr);
  j["status"] = e.status;
  j["verdict"] = to_string(e.verdict);
  j["dimension"] = e.dimension ? nlohmann::ordered_json(*e.dimension) : nlohmann::ordered_json(nullptr);
  return j;
}

ZooEstimate estimate_from_json(const nlohmann::ordered_json& j) {
  ZooEstimate e;
  if (!j.at("value").is_null()) e.value = real_from_json(j.at("value"));
  if (!j.at("interval").is_null())
    e.interval = Interval{real_from_json(j.at("interval").at(0)), real_from_json(j.at("interval").at(1))};
  e.status = j.at("status").get<std::string>();
  e.verdict = verdict_from_string(j.at("verdict").get<std::string>());
  if (!j.at("dimension").is_null()) e.dimension = j.at("dimension").get<std::size_t>();
  return e;
}

nlohmann::ordered_json band_to_json(const ZooBand& b) {
  nlohmann::ordered_json accepted = nlohmann::ordered_json::array();
  for (const auto& i : b.accepted) accepted.push_back({real_json(i.low), real_json(i.high)});
  return {{"accepted", std::move(accepted)}, {"source", b.source}};
}

ZooBand band_from_json(const nlohmann::ordered_json& j) {
  ZooBand b;
  for (const auto& i : j.at("accepted")) b.accepted.push_back(Interval{real_from_json(i.at(0)), real_from_json(i.at(1))});
  b.source = j.at("source").get<std::string>();
  return b;
}

// The first line: what the file's results depend on besides the case.
nlohmann::ordered_json checkpoint_header(bool fast, std::size_t grid_points) {
  return {{"zoo_checkpoint", checkpoint_format}, {"build", zoo_build_fingerprint()}, {"fast", fast}, {"grid_points", grid_points}};
}

std::string options_text(const nlohmann::ordered_json& h) {
  std::ostringstream s;
  s << std::boolalpha << "build " << h.value("build", std::string("?")) << ", fast " << h.value("fast", false)
    << ", grid points " << h.value("grid_points", std::size_t{0});
  return s.str();
}

}  // namespace

std::string zoo_build_fingerprint() {
  // The file this function was loaded from: the chaos executable, or the Python module.
  Dl_info info{};
  std::string file = "/proc/self/exe";
  if (dladdr(reinterpret_cast<const void*>(&zoo_build_fingerprint), &info) != 0 && info.dli_fname != nullptr &&
      std::filesystem::is_regular_file(info.dli_fname))
    file = info.dli_fname;
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InvalidInput(ErrorCode::io, "zoo: cannot read " + file + " to identify the build of a checkpoint");
  std::uint64_t hash = 14695981039346656037ULL;  // FNV-1a, 64 bits
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    for (std::streamsize k = 0; k < in.gcount(); ++k) {
      hash ^= static_cast<unsigned char>(buffer[static_cast<std::size_t>(k)]);
      hash *= 1099511628211ULL;
    }
  }
  std::ostringstream s;
  s << std::hex;
  s.width(16);
  s.fill('0');
  s << hash;
  return s.str();
}

nlohmann::ordered_json zoo_result_to_json(const ZooCaseResult& result) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const ZooRow& r : result.rows)
    rows.push_back({{"n", r.n}, {"theiler_factor", real_json(r.theiler_factor)}, {"theiler", r.theiler},
                    {"delay", r.delay}, {"dimension", r.dimension}, {"automatic", r.automatic},
                    {"d2", estimate_to_json(r.d2)}, {"rosenstein", estimate_to_json(r.rosenstein)},
                    {"kantz", estimate_to_json(r.kantz)}, {"local_maps", estimate_to_json(r.local_maps)},
                    {"lyapunov", estimate_to_json(r.lyapunov)}, {"d2_answer", estimate_to_json(r.d2_answer)},
                    {"d2_reference", estimate_to_json(r.d2_reference)}, {"d2_band", band_to_json(r.d2_band)},
                    {"note", r.note}});
  return {{"case_index", result.case_index}, {"rows", std::move(rows)}, {"seconds", real_json(result.seconds)},
          {"error", result.error}};
}

ZooCaseResult zoo_result_from_json(const nlohmann::ordered_json& j) {
  ZooCaseResult result;
  result.case_index = j.at("case_index").get<std::size_t>();
  for (const auto& row : j.at("rows")) {
    ZooRow r;
    r.n = row.at("n").get<std::size_t>();
    r.theiler_factor = real_from_json(row.at("theiler_factor"));
    r.theiler = row.at("theiler").get<std::size_t>();
    r.delay = row.at("delay").get<std::size_t>();
    r.dimension = row.at("dimension").get<std::size_t>();
    r.automatic = row.at("automatic").get<bool>();
    r.d2 = estimate_from_json(row.at("d2"));
    r.rosenstein = estimate_from_json(row.at("rosenstein"));
    r.kantz = estimate_from_json(row.at("kantz"));
    r.local_maps = estimate_from_json(row.at("local_maps"));
    r.lyapunov = estimate_from_json(row.at("lyapunov"));
    r.d2_answer = estimate_from_json(row.at("d2_answer"));
    r.d2_reference = estimate_from_json(row.at("d2_reference"));
    r.d2_band = band_from_json(row.at("d2_band"));
    r.note = row.at("note").get<std::string>();
    result.rows.push_back(std::move(r));
  }
  result.seconds = real_from_json(j.at("seconds"));
  result.error = j.at("error").get<std::string>();
  return result;
}

ZooCheckpoint::ZooCheckpoint(const std::string& path, bool fast, std::size_t grid_points) : path_(path) {
  const nlohmann::ordered_json expected = checkpoint_header(fast, grid_points);
  std::uintmax_t keep = 0;  // bytes of whole lines to keep: a run killed while writing leaves a cut line
  bool has_header = false;
  if (std::filesystem::exists(path)) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InvalidInput(ErrorCode::io, "zoo: cannot read the checkpoint " + path);
    std::string line;
    std::size_t number = 0;
    std::uintmax_t offset = 0;
    while (std::getline(in, line)) {
      ++number;
      const bool complete = !in.eof();  // ended by a newline
      const std::uintmax_t next = offset + line.size() + (complete ? 1 : 0);
      if (!complete && has_header) break;  // cut short by a killed run: dropped below
      nlohmann::ordered_json j = nlohmann::ordered_json::parse(line, nullptr, false);
      if (j.is_discarded())
        throw InvalidInput(ErrorCode::invalid_parameter, "zoo: line " + std::to_string(number) + " of the checkpoint " +
                                                             path + " is not JSON: not a file `chaos zoo` wrote");
      if (!has_header) {
        if (!complete || !j.is_object() || !j.contains("zoo_checkpoint"))
          throw InvalidInput(ErrorCode::invalid_parameter,
                             "zoo: " + path + " does not start with a zoo checkpoint's first line: not a file `chaos zoo --checkpoint` wrote");
        if (j != expected)
          throw InvalidInput(ErrorCode::invalid_parameter,
                             "zoo: the checkpoint " + path + " was written by another build or with other options (" +
                                 options_text(j) + "; this run: " + options_text(expected) +
                                 "); its results cannot join this run's report: give another file or delete it");
        has_header = true;
      } else {
        try {
          results_[j.at("case").get<std::string>()] = zoo_result_from_json(j.at("result"));
        } catch (const std::exception& e) {
          throw InvalidInput(ErrorCode::invalid_parameter, "zoo: line " + std::to_string(number) + " of the checkpoint " +
                                                               path + " is not a case result (" + e.what() + ")");
        }
      }
      offset = next;
      keep = offset;
    }
    in.close();
    std::error_code ec;
    if (std::filesystem::file_size(path, ec) != keep) std::filesystem::resize_file(path, keep, ec);
    if (ec) throw InvalidInput(ErrorCode::io, "zoo: cannot drop the cut last line of the checkpoint " + path + ": " + ec.message());
  }
  out_.open(path, std::ios::binary | std::ios::app);
  if (!out_) throw InvalidInput(ErrorCode::io, "zoo: cannot write the checkpoint " + path);
  if (!has_header) out_ << expected.dump() << '\n' << std::flush;
  if (!out_) throw InvalidInput(ErrorCode::io, "zoo: cannot write the checkpoint " + path);
}

void ZooCheckpoint::append(const std::string& case_name, const ZooCaseResult& result) {
  const nlohmann::ordered_json line = {{"case", case_name}, {"result", zoo_result_to_json(result)}};
  out_ << line.dump() << '\n' << std::flush;
  if (!out_) throw InvalidInput(ErrorCode::io, "zoo: cannot write to the checkpoint " + path_);
  results_[case_name] = result;
}

}  // namespace chaos::cli
