#include "boxpile/sim/io/json_input.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "boxpile/sim/limits.hpp"

namespace boxpile::json_input {
namespace {

using nlohmann::json;

// A candidate counts as a plausible typo when its edit distance is at most a third of its length
// (at least 1): "half_extent" -> "half_extents", "gravty" -> "gravity", but "zzz" suggests nothing
// and the message lists the valid names instead.
constexpr std::size_t kTypoLengthPerEdit = 3;

// A quaternion or direction whose norm is below this was written as zero: its direction would be
// decided by the rounding of the user's digits, not by the user. Real input has norm ~1.
constexpr double kMinNormalisableNorm = 1e-6;

// Any user's text quoted in a message is cut to this many bytes (in_quotes).
constexpr std::size_t kMaxQuotedBytes = 200;
// Long string values are cut to this many characters when quoted in a message.
constexpr std::size_t kMaxQuotedChars = 40;

std::string quoted_list(std::span<const std::string_view> names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + in_quotes(names[i]);
  return out;
}

// "number 5", "string \"abc\"", "array": what a value is, for "expected X, got Y".
std::string describe(const json& value) {
  switch (value.type()) {
    case json::value_t::string: {
      std::string s = value.get<std::string>();
      if (s.size() > kMaxQuotedChars) s = s.substr(0, kMaxQuotedChars) + "...";
      return "string " + in_quotes(s);
    }
    case json::value_t::number_float:
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::boolean:
      return std::string(value.type_name()) + " " + value.dump();
    default:
      return value.type_name();
  }
}

std::string append_key(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string append_index(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

// Builds the document from the parser's SAX events, knowing at every moment the JSON path of the
// value being read (which nlohmann does not report) and catching a key given twice in one object
// (which nlohmann silently collapses). Linear in the size of the text: nlohmann's parser with a
// callback re-examines the containers built so far and is quadratic in the length of one array
// (200,000 bodies: 14 s), this is not.
class DocumentBuilder {
 public:
  explicit DocumentBuilder(std::string source) : source_(std::move(source)) {}

  json& document() { return root_; }

  // --- nlohmann's SAX interface ---
  bool null() { return add(json(nullptr)); }
  bool boolean(bool b) { return add(json(b)); }
  bool number_integer(json::number_integer_t i) { return add(json(i)); }
  bool number_unsigned(json::number_unsigned_t u) { return add(json(u)); }
  bool number_float(json::number_float_t x, const json::string_t&) { return add(json(x)); }
  bool string(json::string_t& s) { return add(json(std::move(s))); }
  bool binary(json::binary_t& b) { return add(json::binary(std::move(b))); }
  bool start_object(std::size_t) { return open(json::object()); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(json::string_t& k) {
    Frame& f = frames_.back();
    if (f.container->contains(k)) {
      f.key = k;
      throw InputError(source_, path(false), "duplicate key " + in_quotes(k) + ": JSON would keep only the last one");
    }
    f.key = std::move(k);
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) {
    error_id_ = e.id;
    error_what_ = e.what();
    if (const auto* pe = dynamic_cast<const json::parse_error*>(&e)) error_byte_ = pe->byte;
    error_path_ = path(true);
    return false;
  }

  // After a failed parse: nlohmann's exception id, message and byte offset, and the path of the
  // value being read when it failed.
  int error_id() const { return error_id_; }
  const std::string& error_what() const { return error_what_; }
  std::size_t error_byte() const { return error_byte_; }
  const std::string& error_path() const { return error_path_; }

 private:
  struct Frame {
    json* container;
    std::string key;  // objects: the key being read
  };

  // The path of the value most recently begun; with `pending`, of the value the parser is reading
  // now but has not reported yet (a number that failed to convert).
  std::string path(bool pending) const {
    std::string out;
    for (std::size_t k = 0; k < frames_.size(); ++k) {
      const Frame& f = frames_[k];
      const bool innermost = k + 1 == frames_.size();
      if (f.container->is_object()) {
        out = append_key(out, f.key);
      } else {
        const std::size_t size = f.container->size();
        out = append_index(out, innermost && pending ? size : (size == 0 ? 0 : size - 1));
      }
    }
    return out;
  }

  // Places a value in the innermost container (or as the root) and returns where it now lives.
  json* place(json&& value) {
    if (frames_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    Frame& f = frames_.back();
    if (f.container->is_array()) {
      f.container->push_back(std::move(value));
      return &f.container->back();
    }
    json& slot = (*f.container)[f.key];
    slot = std::move(value);
    return &slot;
  }
  bool add(json&& value) {
    place(std::move(value));
    return true;
  }
  // A container stays where it was placed while it is being filled: its parent grows only after
  // it is closed.
  bool open(json&& container) {
    frames_.push_back({place(std::move(container)), {}});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }

  std::string source_;
  json root_;
  std::vector<Frame> frames_;
  int error_id_ = 0;
  std::string error_what_;
  std::size_t error_byte_ = 0;
  std::string error_path_;
};

// Where a byte offset lies in the text, as people count: line and column from 1.
struct TextPosition {
  std::size_t line = 1;
  std::size_t column = 1;
};

TextPosition position_of(const std::string& text, std::size_t byte) {
  // nlohmann's parse_error::byte is the 1-based index of the last character read (one past the
  // end when the input ran out); make it a 0-based index into the text.
  const std::size_t pos = std::min(byte == 0 ? 0 : byte - 1, text.size());
  TextPosition p;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < pos; ++i) {
    if (text[i] == '\n') {
      ++p.line;
      line_start = i + 1;
    }
  }
  // Columns count characters, not bytes: skip UTF-8 continuation bytes (10xxxxxx).
  for (std::size_t i = line_start; i < pos; ++i) {
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++p.column;
  }
  return p;
}

// nlohmann's explanation without its own "[json.exception...] parse error at ...: " prefix, which
// counts lines differently from us, and without a leading "syntax error" we already say.
std::string syntax_detail(const std::string& what) {
  std::string detail = what;
  if (const auto col = detail.find("column "); col != std::string::npos) {
    if (const auto colon = detail.find(": ", col); colon != std::string::npos) {
      detail = detail.substr(colon + 2);
    }
  } else if (const auto bracket = detail.find("] "); bracket != std::string::npos) {
    detail = detail.substr(bracket + 2);
  }
  constexpr std::string_view kPrefix = "syntax error ";
  if (detail.starts_with(kPrefix)) detail = detail.substr(kPrefix.size());
  return detail;
}

// nlohmann's exception id for a number literal that does not fit a double (e.g. 1e999).
constexpr int kNumberOverflowId = 406;

}  // namespace

std::string read_text_file(const std::string& path, std::size_t max_bytes) {
  // Opened without blocking (a FIFO without a writer would wait forever), then checked by its
  // descriptor, so that what is read is what was checked.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw InputError(path, "", std::string("cannot open: ") + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw InputError(path, "", std::string("cannot open: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw InputError(path, "", "cannot open: it is a directory");
  if (!S_ISREG(st.st_mode)) {
    throw InputError(path, "", "cannot open: not a regular file (a device, FIFO or socket is not read)");
  }
  const std::string cap = "above the cap of " + std::to_string(max_bytes) + " bytes (--max-input-bytes raises it)";
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) {
    throw InputError(path, "", std::to_string(st.st_size) + " bytes, " + cap);
  }
  std::string text;
  text.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(path, "", std::string("cannot read: ") + std::strerror(errno));
    if (n == 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    if (text.size() > max_bytes) throw InputError(path, "", "more than " + std::to_string(max_bytes) + " bytes (it grew while read), " + cap);
  }
  return text;
}

json parse(const std::string& text, const std::string& source) {
  // nlohmann stops reading at a NUL byte and would silently ignore the rest of the file.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    const TextPosition p = position_of(text, nul + 1);
    throw InputError(source, "",
                     "a NUL byte at line " + std::to_string(p.line) + ", column " + std::to_string(p.column) +
                         ": not a JSON text file");
  }
  DocumentBuilder builder(source);
  if (json::sax_parse(text, &builder)) return std::move(builder.document());
  if (builder.error_id() == kNumberOverflowId) {
    throw InputError(source, builder.error_path(), "number out of range: must be finite");
  }
  const TextPosition p = position_of(text, builder.error_byte());
  throw InputError(source, "",
                   "JSON syntax error at line " + std::to_string(p.line) + ", column " + std::to_string(p.column) +
                       ": " + shortened(syntax_detail(builder.error_what())));
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Optimal string alignment distance (Damerau's transposition added to Levenshtein's dynamic
  // programme over prefixes): d[i][j] is the distance between a[0, i) and b[0, j).
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1, 0));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

std::optional<std::string_view> closest_match(std::string_view word,
                                              std::span<const std::string_view> candidates) {
  std::optional<std::string_view> best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (std::string_view c : candidates) {
    const std::size_t d = edit_distance(word, c);
    const std::size_t allowed = std::max<std::size_t>(1, c.size() / kTypoLengthPerEdit);
    if (d <= allowed && d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  return best;
}

namespace {

// The code point of the UTF-8 sequence at s[i] and its length; length 0 for a byte that starts
// no valid sequence (a stray continuation byte, a cut or overlong sequence).
std::pair<char32_t, std::size_t> utf8_at(std::string_view s, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char lead = b(i);
  if (lead < 0x80) return {lead, 1};
  const std::size_t n = lead >= 0xF0 && lead <= 0xF4 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC2 && lead < 0xE0 ? 2 : 0;
  if (n == 0 || i + n > s.size()) return {0, 0};
  char32_t c = lead & (0x7F >> n);
  for (std::size_t k = 1; k < n; ++k) {
    if ((b(i + k) & 0xC0) != 0x80) return {0, 0};
    c = (c << 6) | (b(i + k) & 0x3F);
  }
  if ((n == 3 && c < 0x800) || (n == 4 && (c < 0x10000 || c > 0x10FFFF)) || (c >= 0xD800 && c <= 0xDFFF)) return {0, 0};
  return {c, n};
}

bool is_c1_control(char32_t c) { return c >= 0x80 && c <= 0x9F; }

bool is_bidi_control(char32_t c) {
  return c == 0x061C || c == 0x200E || c == 0x200F || (c >= 0x202A && c <= 0x202E) || (c >= 0x2066 && c <= 0x2069);
}

// Characters that draw nothing: white space, the non-breaking and zero-width spaces, joiners,
// fillers, the byte order mark, and the bidirectional controls.
bool is_invisible(char32_t c) {
  return c == ' ' || c == '\t' || c == 0xA0 || c == 0xAD || c == 0x034F || c == 0x115F || c == 0x1160 ||
         c == 0x180E || (c >= 0x2000 && c <= 0x200F) || (c >= 0x2028 && c <= 0x202F) ||
         (c >= 0x205F && c <= 0x206F) || c == 0x3000 || c == 0x3164 || c == 0xFEFF || c == 0xFFA0 || is_bidi_control(c);
}

void append_escape(std::string& out, const char* format, unsigned value) {
  char escaped[12];
  std::snprintf(escaped, sizeof escaped, format, value);
  out += escaped;
}

}  // namespace

std::size_t whole_utf8_prefix(std::string_view s) {
  // A cut sequence can only be among the last three bytes.
  for (std::size_t back = 1; back <= 3 && back <= s.size(); ++back) {
    const auto u = static_cast<unsigned char>(s[s.size() - back]);
    if ((u & 0xC0) == 0x80) continue;  // a continuation byte: look further back
    const std::size_t n = u >= 0xF0 ? 4 : u >= 0xE0 ? 3 : u >= 0xC0 ? 2 : 1;
    return n > back ? s.size() - back : s.size();
  }
  return s.size();
}

std::string terminal_safe(std::string_view s, bool keep_layout) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const auto [c, n] = utf8_at(s, i);
    if (n == 0) {
      append_escape(out, "\\x%02x", static_cast<unsigned char>(s[i]));
      ++i;
      continue;
    }
    if (c < 0x20 || c == 0x7F) {
      const bool layout = c == '\n' || c == '\t' || c == '\r' || (c == 0x1B && s.substr(i, 3) == "\x1b[K");
      if (keep_layout && layout) {
        out.append(s.substr(i, c == 0x1B ? 3 : 1));
        i += c == 0x1B ? 3 : 1;
        continue;
      }
      append_escape(out, "\\x%02x", static_cast<unsigned>(c));
    } else if (is_c1_control(c) || is_bidi_control(c)) {
      append_escape(out, "\\u%04x", static_cast<unsigned>(c));
    } else {
      out.append(s.substr(i, n));
    }
    i += n;
  }
  return out;
}

std::string in_quotes(std::string_view s) {
  // At most kMaxQuotedBytes of the text, cut before a UTF-8 continuation byte, with the length of
  // the whole: a 10 MB key makes a line, not a 10 MB message.
  std::string_view shown = s;
  if (shown.size() > kMaxQuotedBytes) {
    std::size_t cut = kMaxQuotedBytes;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
    shown = s.substr(0, cut);
  }
  // Control characters are shown escaped, so that a message never moves the cursor, rings or
  // clears the terminal that prints it, nor reorders the line.
  std::string out = "\"" + terminal_safe(shown);
  out.push_back('"');
  if (shown.size() < s.size()) out += "... (" + std::to_string(s.size()) + " characters)";
  return out;
}

std::string shortened(std::string_view s) {
  std::string quoted = in_quotes(s);
  // The same cut and escapes without the quotes, for text that is not a name (a parser's detail).
  const std::size_t close = quoted.rfind('"');
  return quoted.substr(1, close - 1) + quoted.substr(close + 1);
}

std::string format_number(double x) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

// ---------------------------------------------------------------------------------------------
// JsonNode

JsonNode::JsonNode(const nlohmann::json& root, std::string source)
    : JsonNode(root, std::move(source), "") {}

JsonNode::JsonNode(const nlohmann::json& value, std::string source, std::string path)
    : value_(&value), source_(std::move(source)), path_(std::move(path)) {}

void JsonNode::fail(const std::string& what) const { throw InputError(source_, path_, what); }

void JsonNode::fail_type(std::string_view expected) const {
  fail("expected " + std::string(expected) + ", got " + describe(*value_));
}

JsonNode JsonNode::child(std::string_view key) const {
  return JsonNode(value_->find(key).value(), source_, append_key(path_, key));
}

void JsonNode::expect_object(std::initializer_list<std::string_view> allowed) const {
  expect_object(std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

void JsonNode::expect_object(std::span<const std::string_view> names) const {
  if (!value_->is_object()) fail_type("object");
  for (const auto& item : value_->items()) {
    const std::string& key = item.key();
    if (std::find(names.begin(), names.end(), key) != names.end()) continue;
    if (const auto guess = closest_match(key, names)) {
      fail("unknown key " + in_quotes(key) + "; did you mean " + in_quotes(*guess) + "?");
    }
    fail("unknown key " + in_quotes(key) + "; valid keys are " + quoted_list(names));
  }
}

bool JsonNode::has(std::string_view key) const {
  return value_->is_object() && value_->contains(key);
}

JsonNode JsonNode::at(std::string_view key) const {
  if (!value_->is_object()) fail_type("object");
  if (!value_->contains(key)) fail("missing required key " + in_quotes(key));
  return child(key);
}

std::optional<JsonNode> JsonNode::find(std::string_view key) const {
  if (!value_->is_object()) fail_type("object");
  if (!value_->contains(key)) return std::nullopt;
  return child(key);
}

std::size_t JsonNode::array_size() const {
  if (!value_->is_array()) fail_type("array");
  return value_->size();
}

void JsonNode::expect_array_size(std::size_t n) const {
  const std::size_t size = array_size();
  if (size != n) {
    fail("expected an array of " + std::to_string(n) + " elements, got " + std::to_string(size));
  }
}

JsonNode JsonNode::element(std::size_t i) const {
  if (i >= array_size()) fail("has no element " + std::to_string(i));
  return JsonNode((*value_)[i], source_, append_index(path_, i));
}

double JsonNode::number() const {
  if (!value_->is_number()) fail_type("number");
  const double x = value_->get<double>();
  if (!std::isfinite(x)) fail("must be finite, got " + format_number(x));
  return x;
}

int JsonNode::integer() const {
  constexpr auto kMin = std::numeric_limits<int>::min();
  constexpr auto kMax = std::numeric_limits<int>::max();
  if (value_->is_number_unsigned()) {
    const auto u = value_->get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(kMax)) fail("integer out of range: " + value_->dump());
    return static_cast<int>(u);
  }
  if (value_->is_number_integer()) {
    const auto i = value_->get<std::int64_t>();
    if (i < kMin || i > kMax) fail("integer out of range: " + value_->dump());
    return static_cast<int>(i);
  }
  if (!value_->is_number()) fail_type("integer");
  const double x = number();
  if (x != std::floor(x) || x < kMin || x > kMax) {
    fail("expected an integer, got " + describe(*value_));
  }
  return static_cast<int>(x);
}

bool JsonNode::boolean() const {
  if (!value_->is_boolean()) fail_type("boolean");
  return value_->get<bool>();
}

std::string JsonNode::string() const {
  if (!value_->is_string()) fail_type("string");
  return value_->get<std::string>();
}

std::size_t JsonNode::choice(std::span<const std::string_view> names, std::string_view what) const {
  const std::string s = string();
  const auto it = std::find(names.begin(), names.end(), s);
  if (it != names.end()) return static_cast<std::size_t>(it - names.begin());
  const std::string head = "unknown " + std::string(what) + " " + in_quotes(s);
  if (const auto guess = closest_match(s, names)) {
    fail(head + "; did you mean " + in_quotes(*guess) + "?");
  }
  fail(head + "; expected one of " + quoted_list(names));
}

double JsonNode::number_or(std::string_view key, double fallback) const {
  const auto node = find(key);
  return node ? node->number() : fallback;
}

int JsonNode::integer_or(std::string_view key, int fallback) const {
  const auto node = find(key);
  return node ? node->integer() : fallback;
}

bool JsonNode::boolean_or(std::string_view key, bool fallback) const {
  const auto node = find(key);
  return node ? node->boolean() : fallback;
}

std::string JsonNode::string_or(std::string_view key, std::string fallback) const {
  const auto node = find(key);
  return node ? node->string() : std::move(fallback);
}

// ---------------------------------------------------------------------------------------------
// Shared value readers

double read_in_range(const JsonNode& node, double lo, double hi, std::string_view unit) {
  const double x = node.number();
  if (x < lo || x > hi) {
    node.fail("must be in [" + format_number(lo) + ", " + format_number(hi) + "]" +
              (unit.empty() ? std::string() : " " + std::string(unit)) + ", got " + format_number(x));
  }
  return x;
}

Vec3 read_vec3(const JsonNode& node, double max_component) {
  node.expect_array_size(3);
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    const JsonNode c = node.element(static_cast<std::size_t>(i));
    v[i] = c.number();
    if (std::abs(v[i]) > max_component) {
      c.fail("must be at most " + format_number(max_component) + " in magnitude, got " + format_number(v[i]));
    }
  }
  return v;
}

Vec3 read_vec3(const JsonNode& node) { return read_vec3(node, limits::kMaxCoordinate); }

Vec3 read_bounded_vector(const JsonNode& node, double max_norm, std::string_view unit) {
  const Vec3 v = read_vec3(node);
  if (v.norm() > max_norm) {
    node.fail("magnitude " + format_number(v.norm()) + " " + std::string(unit) + " is above the limit of " +
              format_number(max_norm) + " " + std::string(unit));
  }
  return v;
}

Vec3 read_half_extents(const JsonNode& node, double min_half_extent) {
  node.expect_array_size(3);
  Vec3 h;
  for (int i = 0; i < 3; ++i) {
    const JsonNode c = node.element(static_cast<std::size_t>(i));
    h[i] = read_positive(c);
    if (h[i] < min_half_extent || h[i] > limits::kMaxHalfExtent) {
      c.fail("must be in [" + format_number(min_half_extent) + ", " + format_number(limits::kMaxHalfExtent) +
             "] m, got " + format_number(h[i]));
    }
  }
  return h;
}

Quat read_orientation(const JsonNode& node) {
  node.expect_array_size(4);
  // Each component is bounded before the norm is taken, so that the norm cannot overflow.
  double c[4];
  for (int i = 0; i < 4; ++i) {
    const JsonNode e = node.element(static_cast<std::size_t>(i));
    c[i] = e.number();
    if (std::abs(c[i]) > limits::kMaxDirectionComponent) {
      e.fail("must be at most " + format_number(limits::kMaxDirectionComponent) + " in magnitude, got " +
             format_number(c[i]));
    }
  }
  // JSON quaternions are [w, x, y, z]; Eigen's constructor takes them in that order too.
  const Quat q(c[0], c[1], c[2], c[3]);
  if (!(q.norm() >= kMinNormalisableNorm)) {
    node.fail("zero quaternion (norm " + format_number(q.norm()) +
              ") is not a rotation; [w, x, y, z] = [1, 0, 0, 0] is the identity");
  }
  return q.normalized();
}

Vec3 read_direction(const JsonNode& node) {
  const Vec3 d = read_vec3(node, limits::kMaxDirectionComponent);
  if (!(d.norm() >= kMinNormalisableNorm)) {
    node.fail("zero vector (norm " + format_number(d.norm()) + ") has no direction");
  }
  return d.normalized();
}

double read_non_negative(const JsonNode& node) {
  const double x = node.number();
  if (x < 0.0) node.fail("must be >= 0, got " + format_number(x));
  return x;
}

double read_positive(const JsonNode& node) {
  const double x = node.number();
  if (x <= 0.0) node.fail("must be > 0, got " + format_number(x));
  return x;
}

std::string read_name(const JsonNode& node) {
  std::string s = node.string();
  if (s.empty()) node.fail("must not be empty");
  const bool blank = std::all_of(s.begin(), s.end(), [](char c) { return c == ' ' || c == '\t'; });
  if (blank) node.fail("must not be only white space");
  bool visible = false;
  for (std::size_t i = 0; i < s.size();) {
    const auto [c, n] = utf8_at(s, i);
    if (n == 0) node.fail("must be UTF-8, got " + in_quotes(s));  // (nlohmann's parser already refuses it)
    if (c < 0x20 || c == 0x7F || is_c1_control(c)) node.fail("must not contain control characters, got " + in_quotes(s));
    visible = visible || !is_invisible(c);
    i += n;
  }
  if (!visible) {
    // Shown code point by code point: the name itself would print as nothing.
    std::string shown;
    for (std::size_t i = 0; i < s.size();) {
      const auto [c, n] = utf8_at(s, i);
      append_escape(shown, "U+%04X ", static_cast<unsigned>(c));
      i += n;
    }
    shown.pop_back();
    node.fail("must not be only invisible characters (white space, non-breaking or zero-width spaces, joiners), "
              "got " + shown);
  }
  return s;
}

HalfSpace read_half_space(const JsonNode& node) {
  node.expect_object({"normal", "offset"});
  HalfSpace h;
  if (const auto normal = node.find("normal")) h.normal = read_direction(*normal);
  if (const auto offset = node.find("offset")) {
    h.offset = read_in_range(*offset, -limits::kMaxCoordinate, limits::kMaxCoordinate, "m");
  }
  return h;
}

}  // namespace boxpile::json_input
