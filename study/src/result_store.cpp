#include "study/result_store.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "chaos/format.hpp"
#include "mechanism/scene.hpp"
#include "safe_output.hpp"
#include "study/error.hpp"
#include "study/series_analysis.hpp"

namespace study {

namespace fs = std::filesystem;

namespace {

std::string number(double v) { return chaos::format_number(v, chaos::Precision::table); }

std::string optional_number(const std::optional<double>& v) { return v ? number(*v) : "-"; }

std::string read_file(const fs::path& path) {
  std::error_code error;
  if (fs::is_directory(path, error)) throw StudyError("file", path.string(), "is a directory, not a file of the sweep");
  std::ifstream in(path);
  if (!in) throw StudyError("file", path.string(), "cannot be read");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\t' || c == '\n') c = ' ';
  return s;
}

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> f;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i)
    if (i == line.size() || line[i] == '\t') {
      f.push_back(line.substr(start, i - start));
      start = i + 1;
    }
  return f;
}

std::string join_from(const std::vector<std::string>& f, std::size_t first) {
  std::string s;
  for (std::size_t i = first; i < f.size(); ++i) s += (i > first ? "\t" : "") + f[i];
  return s;
}

std::string commented(const std::string& text) {
  std::istringstream in(text);
  std::string out;
  for (std::string line; std::getline(in, line);) out += "# " + line + "\n";
  return out;
}

// A spec's text without its "analysis.rules = N" line, and the revision that line names: a resume
// whose spec differs only there is refused with its own reason (series_analysis.hpp).
constexpr const char* rules_key = "analysis.rules = ";

std::string without_rules_line(const std::string& text) {
  std::istringstream in(text);
  std::string out;
  for (std::string line; std::getline(in, line);)
    if (line.rfind(rules_key, 0) != 0) out += line + "\n";
  return out;
}

std::string rules_revision(const std::string& text) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(rules_key, 0) == 0) return "revision " + line.substr(std::strlen(rules_key));
  return "revision 1 (a spec without an analysis.rules line, written before the revision was recorded)";
}

// The first line where two texts differ, for the resume refusal.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream ia(a), ib(b);
  std::string la, lb;
  while (true) {
    const bool ga = static_cast<bool>(std::getline(ia, la)), gb = static_cast<bool>(std::getline(ib, lb));
    if (!ga && !gb) return "";
    if (!ga || !gb || la != lb) return "'" + (ga ? la : std::string("(end)")) + "' was '" + (gb ? lb : std::string("(end)")) + "'";
  }
}

// FNV-1a, 64 bits, as 16 hex digits: a point file names the spec it was computed for.
std::string text_hash(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

// Takes DIR/lock for this process (released by close or exit, even a kill). Refuses, naming the
// holder's process id written in the file, when another sweep holds it.
int take_lock(const fs::path& dir) {
  const fs::path path = dir / "lock";
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw StudyError("-o", path.string(), std::string("cannot be opened: ") + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    char holder[64] = {};
    const ssize_t n = ::pread(fd, holder, sizeof holder - 1, 0);
    ::close(fd);
    std::string who = n > 0 ? std::string(holder, static_cast<std::size_t>(n)) : std::string();
    while (!who.empty() && (who.back() == '\n' || who.back() == ' ')) who.pop_back();
    if (error != EWOULDBLOCK) throw StudyError("-o", path.string(), std::string("cannot be locked: ") + std::strerror(error));
    throw StudyError("-o", dir.string(),
                     "is in use by another sweep (" + (who.empty() ? std::string("process unknown") : who) +
                         " holds " + path.string() + "); wait for it to finish or choose another directory");
  }
  const std::string me = "process " + std::to_string(::getpid()) + "\n";
  errno = 0;
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, me.data(), me.size(), 0) != static_cast<ssize_t>(me.size())) {
    const int error = errno ? errno : EIO;  // a short write sets none
    ::close(fd);
    throw StudyError("-o", path.string(), std::string("cannot be written (") + std::strerror(error) + ")",
                     StudyError::Kind::io);
  }
  return fd;
}

}  // namespace

void write_atomically(const fs::path& path, const std::string& text) {
  try {
    safe_output::write_file(path.string(), text);
  } catch (const safe_output::WriteError& e) {
    throw StudyError(e.what(), StudyError::Kind::io);  // exit 4, as every input/output failure of the study
  }
}

ResultStore::ResultStore(fs::path dir, const SweepSpec& spec, bool resume, bool lock)
    : dir_(std::move(dir)), spec_(spec), header_(spec.describe()), spec_hash_(text_hash(header_)) {
  const fs::path spec_file = dir_ / "spec.txt";
  if (fs::exists(dir_) && !fs::is_directory(dir_)) throw StudyError("-o", dir_.string(), "exists and is not a directory");
  // The lock comes before anything is read: two sweeps started at once into one directory would
  // otherwise both find it empty and mix their points.
  const bool existed = fs::exists(dir_);
  fs::create_directories(dir_);
  if (lock) lock_fd_ = take_lock(dir_);
  try {
    if (fs::exists(spec_file)) {
      if (!resume)
        throw StudyError("-o", dir_.string(),
                         "already holds a sweep; add --resume to continue it, or choose a new directory");
      const std::string old = read_file(spec_file);
      if (old != header_ && without_rules_line(old) == without_rules_line(header_))
        throw StudyError("--resume", dir_.string(),
                         "its points were analysed under " + rules_revision(old) +
                             " of the series-analysis rules and this build uses revision " +
                             std::to_string(analysis_rules_revision) +
                             " (study/series_analysis.hpp lists the changes); they would not compare with new "
                             "points: run the sweep into a new directory");
      if (old != header_)
        throw StudyError("--resume", dir_.string(),
                         "the directory holds another sweep; first difference: " + first_difference(header_, old));
    }
    fs::create_directories(dir_ / "points");
    if (!fs::exists(spec_file)) write_atomically(spec_file, header_);
  } catch (...) {
    // A refused request leaves no directory behind that it created itself.
    if (lock_fd_ >= 0) ::close(lock_fd_);
    lock_fd_ = -1;
    if (!existed) fs::remove_all(dir_);
    throw;
  }
  if (!lock) return;  // another rank holds the lock and has cleaned the directory
  // A killed run leaves at most one temporary file per point it was writing: never a result.
  for (const auto& entry : fs::directory_iterator(dir_ / "points"))
    if (entry.path().filename().string().find(".tmp.") != std::string::npos) fs::remove(entry.path());
  // A point file cut short (a full disk, a copy interrupted), edited, or left by another spec is
  // deleted, so the sweep recomputes that point instead of assembling what is left of it.
  for (std::size_t p = 0; p < spec_.grid.size(); ++p) {
    const fs::path path = point_path(p);
    if (!fs::exists(path)) continue;
    const std::string why = check_point_file(p, read_file(path));
    if (why.empty()) continue;
    discarded_.push_back("point " + std::to_string(p) + " (" + path.string() + "): " + why);
    fs::remove(path);
  }
}

ResultStore::~ResultStore() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

std::string ResultStore::check_point_file(std::size_t point, const std::string& text) const {
  if (text.rfind("# study point " + std::to_string(point) + "\n", 0) != 0) return "does not begin with its header";
  if (text.size() < 4 || text.compare(text.size() - 4, 4, "end\n") != 0) return "is incomplete (no end line)";
  std::istringstream in(text);
  std::map<std::string, std::vector<std::string>> fields;
  std::size_t samples = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    auto f = split_tabs(line);
    if (f[0] == "sample") ++samples;
    else if (f[0] != "check") fields[f[0]] = std::move(f);
  }
  if (!fields.count("spec") || fields["spec"].size() < 2 || fields["spec"][1] != spec_hash_)
    return "was computed for another spec (its hash is not " + spec_hash_ + ")";
  // The check line holds the hash of everything above it: a file edited or garbled in place
  // (a field changed, a byte flipped) was assembled as it was (corrupt-file tier).
  const std::size_t check_at = text.rfind("\ncheck\t");
  if (check_at == std::string::npos) return "has no check line (damaged, or written before point files had one)";
  if (text.compare(check_at + 1, std::string::npos, "check\t" + text_hash(text.substr(0, check_at + 1)) + "\nend\n") != 0)
    return "is damaged (its contents do not match its check line)";
  for (const char* key : {"coordinates", "status", "counters", "wall_seconds", "final_state"})
    if (!fields.count(key)) return std::string("has no ") + key + " line";
  if (spec_.analyse && !fields.count("analysis")) return "has no analysis line";
  if (spec_.lyapunov && !fields.count("lyapunov")) return "has no lyapunov line";
  const auto& counters = fields["counters"];
  if (counters.size() < 8) return "has a short counters line";
  if (counters[7] != std::to_string(samples))
    return "has " + std::to_string(samples) + " sample rows where its counters say " + counters[7];
  return {};
}

fs::path ResultStore::point_path(std::size_t point) const {
  char name[32];
  std::snprintf(name, sizeof name, "%06zu.tsv", point);
  return dir_ / "points" / name;
}

bool ResultStore::finished(std::size_t point) const { return fs::exists(point_path(point)); }

void ResultStore::write(const PointResult& r) const {
  std::ostringstream o;
  o << "# study point " << r.point << "\nspec\t" << spec_hash_ << "\ncoordinates";
  for (double c : r.coordinates) o << "\t" << exact(c);
  const auto& s = r.summary;
  o << "\nstatus\t" << mechanism::to_string(s.status) << "\t" << one_line(s.message) << "\n"
    << "counters\t" << s.steps << "\t" << s.rejected_steps << "\t" << s.rhs_evaluations << "\t"
    << number(s.max_penetration) << "\t" << s.contact_events << "\t" << number(s.energy_balance_relative) << "\t"
    << r.samples.size() << "\n"
    << "wall_seconds\t" << number(s.wall_seconds) << "\nfinal_state";
  for (double v : s.final_state) o << "\t" << exact(v);
  o << "\n";
  if (r.analysis) {
    const SeriesAnalysis& a = *r.analysis;
    const std::size_t m = spec_.analysis.max_dimension;
    auto at = [&](const std::vector<double>& v, std::size_t k) { return k < v.size() ? number(v[k]) : std::string("-"); };
    o << "analysis\t" << one_line(a.status) << "\t" << a.samples << "\t" << number(a.interval) << "\t"
      << (a.delay ? std::to_string(*a.delay) : "-") << "\t" << (a.delay ? number(static_cast<double>(*a.delay) * a.interval) : "-") << "\t"
      << a.theiler << "\t" << (a.embedding_dimension ? std::to_string(*a.embedding_dimension) : "-") << "\t"
      << (a.E2.empty() ? "-" : number(a.e2_deviation)) << "\t" << a.d2_status << "\t" << optional_number(a.d2) << "\t"
      << optional_number(a.d2_low) << "\t" << optional_number(a.d2_high);
    for (std::size_t k = 0; k < m; ++k) o << "\t" << at(a.E1, k);
    for (std::size_t k = 0; k < m; ++k) o << "\t" << at(a.E2, k);
    for (std::size_t k = 0; k < m; ++k)
      o << "\t" << (k < a.d2_by_dimension.size() ? optional_number(a.d2_by_dimension[k]) : "-");
    o << "\t" << one_line(a.nonlinearity) << "\t" << (a.nonlinearity_rank ? std::to_string(*a.nonlinearity_rank) : "-")
      << "\t" << (a.surrogates ? std::to_string(a.surrogates) : "-");
    o << "\n";
  }
  if (r.lyapunov) {
    // status, periods, then K exponents, K standard errors ('-' past the phase space or -inf), D_KY
    // of the attractor and of the section, the largest separation, the message.
    const mechanism::SceneLyapunov& l = *r.lyapunov;
    const std::size_t k = spec_.lyapunov_options.exponents;
    auto at = [](const std::vector<double>& v, std::size_t i) {
      return i < v.size() && std::isfinite(v[i]) ? number(v[i]) : std::string("-");
    };
    o << "lyapunov\t" << l.status << "\t" << l.periods;
    for (std::size_t i = 0; i < k; ++i) o << "\t" << at(l.exponents, i);
    for (std::size_t i = 0; i < k; ++i) o << "\t" << at(l.standard_error, i);
    o << "\t" << (std::isfinite(l.kaplan_yorke) ? number(l.kaplan_yorke) : "-") << "\t"
      << (std::isfinite(l.kaplan_yorke_section) ? number(l.kaplan_yorke_section) : "-") << "\t"
      << number(l.largest_separation) << "\t" << one_line(l.message) << "\n";
  }
  for (const auto& row : r.samples) {
    o << "sample\t" << static_cast<std::size_t>(row[0]);
    for (std::size_t k = 1; k < row.size(); ++k) o << "\t" << number(row[k]);
    o << "\n";
  }
  std::string text = o.str();
  text += "check\t" + text_hash(text) + "\nend\n";  // the last line: a file without it was cut short
  write_atomically(point_path(r.point), text);
}

std::optional<std::vector<double>> ResultStore::final_state(std::size_t point) const {
  if (!finished(point)) return std::nullopt;
  std::istringstream in(read_file(point_path(point)));
  for (std::string line; std::getline(in, line);) {
    const auto f = split_tabs(line);
    if (f[0] == "status" && (f.size() < 2 || f[1] != mechanism::to_string(mechanism::SimulationStatus::completed)))
      return std::nullopt;
    if (f[0] != "final_state") continue;
    std::vector<double> x;
    for (std::size_t i = 1; i < f.size(); ++i) {
      // std::stod threw std::invalid_argument on a garbled file: an internal error.
      char* end = nullptr;
      const double v = std::strtod(f[i].c_str(), &end);
      if (f[i].empty() || *end != '\0' || !std::isfinite(v))
        throw StudyError("point file", point_path(point).string(),
                         "has a final_state value '" + f[i].substr(0, 40) + "' that is not a finite number; run the sweep "
                         "again with --resume to recompute it");
      x.push_back(v);
    }
    return x;
  }
  return std::nullopt;
}

void ResultStore::assemble() const {
  const Grid& grid = spec_.grid;
  std::string axes_header;
  for (const Axis& a : grid.axes()) axes_header += "\t" + a.key;
  // A short header: the sweep's settings and the base scene as the keys that differ from the built-in
  // scene (with it, the scene in full); spec.txt beside the table holds the whole resolved scene.
  // The tables opened with all of spec.txt, some 190 '#' lines, before their column names.
  const std::string marker = "base scene (resolved, before the axis values):\n";
  std::string head = "# study sweep (docs/reference/study.md); spec.txt beside this file holds every setting and the "
                     "whole resolved base scene\n" +
                     commented(header_.substr(0, header_.find(marker)));
  const std::vector<std::string> changed =
      mechanism::scene_differences(mechanism::read_scene(spec_.scene_text, spec_.overrides, spec_.scene_source));
  head += changed.empty() ? "# base scene: the built-in seed scene, no key changed\n"
                          : "# base scene: the keys that differ from the built-in scene (before the axis values):\n";
  for (const auto& line : changed) head += "#   " + line + "\n";
  std::string samples = head + "# point" + axes_header + "\trevolution\tt";
  for (const auto& s : spec_.signals) samples += "\t" + s;
  samples += "\n";
  std::string points = head +
                       "# point" + axes_header +
                       "\tstatus\tsteps\trejected_steps\trhs_evaluations\tmax_penetration\tcontact_events"
                       "\tenergy_balance_relative\tsamples\tmessage\n";
  std::string analysis = head + "# '-': no value (the status column says why)\n# point" + axes_header +
                         "\tstatus\tsamples\tinterval\tdelay_samples\tdelay_seconds\ttheiler\tcao_dimension"
                         "\te2_deviation\td2_status\td2\td2_low\td2_high";
  for (const char* name : {"E1_", "E2_", "D2_m"})
    for (std::size_t k = 1; k <= spec_.analysis.max_dimension; ++k) {
      analysis += '\t';
      analysis += name;
      analysis += std::to_string(k);
    }
  analysis += "\tnonlinearity\tnonlinearity_rank\tsurrogates\n";
  std::string lyapunov = head + "# Lyapunov exponents from the equations (docs/reference/mechanism/lyapunov.md), 1/s; '-': none\n# point" +
                         axes_header + "\tstatus\tperiods";
  for (const char* name : {"lambda_", "se_"})
    for (std::size_t k = 1; k <= spec_.lyapunov_options.exponents; ++k) {
      lyapunov += '\t';  // appended piece by piece: "\t" + name + ... trips GCC 12's -Wrestrict
      lyapunov += name;
      lyapunov += std::to_string(k);
    }
  lyapunov += "\tkaplan_yorke\tkaplan_yorke_section\tlargest_separation\tmessage\n";
  std::string timing = "# wall seconds per point (the only output that differs between runs)\n# point\twall_seconds\n";
  for (std::size_t p = 0; p < grid.size(); ++p) {
    if (!finished(p)) throw StudyError("assemble", "point " + std::to_string(p), "is not finished");
    const std::string text = read_file(point_path(p));
    if (const std::string why = check_point_file(p, text); !why.empty())
      throw StudyError("point file", point_path(p).string(), why + "; run the sweep again with --resume to recompute it");
    std::istringstream in(text);
    std::string prefix = std::to_string(p);
    for (double c : grid.coordinates(p)) {
      prefix += '\t';
      prefix += number(c);
    }
    std::map<std::string, std::vector<std::string>> fields;
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      auto f = split_tabs(line);
      if (f[0] == "sample") {
        samples += prefix + "\t" + join_from(f, 1) + "\n";
      } else if (f[0] != "end" && f[0] != "check") {
        fields[f[0]] = f;
      }
    }
    const auto& st = fields["status"];
    const auto& cnt = fields["counters"];
    if (st.size() < 2 || cnt.size() < 8) throw StudyError("point file", point_path(p).string(), "is damaged");
    points += prefix + "\t" + st[1] + "\t" + join_from(cnt, 1) + "\t" + (st.size() > 2 ? st[2] : "") + "\n";
    if (spec_.analyse && fields.count("analysis")) analysis += prefix + "\t" + join_from(fields["analysis"], 1) + "\n";
    if (spec_.lyapunov && fields.count("lyapunov")) lyapunov += prefix + "\t" + join_from(fields["lyapunov"], 1) + "\n";
    if (fields.count("wall_seconds")) timing += std::to_string(p) + "\t" + fields["wall_seconds"][1] + "\n";
  }
  write_atomically(dir_ / "samples.tsv", samples);
  write_atomically(dir_ / "points.tsv", points);
  if (spec_.analyse) write_atomically(dir_ / "analysis.tsv", analysis);
  if (spec_.lyapunov) write_atomically(dir_ / "lyapunov.tsv", lyapunov);
  write_atomically(dir_ / "timing.tsv", timing);
}

}  // namespace study
