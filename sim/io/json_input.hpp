// The JSON reading layer shared by the scene and query loaders: every value is read through a
// JsonNode that knows its file and its JSON path ("bodies[3].half_extents[1]"), so that each
// problem becomes an InputError naming the file, the path and what is wrong.
//
// Internal to boxpile::scene_io (the loaders include it; nothing else should need to).
#pragma once

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/math.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile::json_input {

// The whole text of the regular file at `path`, of at most `max_bytes`: InputError(path, "",
// "cannot open: <reason>") otherwise. A device, FIFO or socket is refused without blocking or
// reading it (/dev/zero never ends, a FIFO without a writer never answers); a larger file is
// refused before it is read, naming the cap and its flag.
std::string read_text_file(const std::string& path, std::size_t max_bytes = limits::kDefaultMaxInputBytes);

// Parses JSON text. Syntax errors are reported with line and column; a key given twice in one
// object and a number beyond the range of a double are reported with their JSON path.
nlohmann::json parse(const std::string& text, const std::string& source);

// Edit distance with adjacent transpositions (optimal string alignment): the number of single
// character insertions, deletions, substitutions and swaps that turn `a` into `b`.
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate closest to `word` by edit distance, if it is close enough to be a plausible typo.
std::optional<std::string_view> closest_match(std::string_view word,
                                              std::span<const std::string_view> candidates);

// `s` with everything that could steer a terminal shown escaped: C0 control characters and DEL
// as \xNN (kept when `keep_layout`: newline, tab, carriage return and the erase-line sequence
// ESC [ K that progress lines use), C1 control characters (U+0080 to U+009F, one of which opens
// an escape sequence) and the bidirectional controls (U+061C, U+200E, U+200F, U+202A to U+202E,
// U+2066 to U+2069: they reorder what follows) as \uXXXX, and bytes that are no UTF-8 as \xNN.
// Inside a JSON string \uXXXX reads back as the same character.
std::string terminal_safe(std::string_view s, bool keep_layout = false);
// How many leading bytes of `s` end on a whole UTF-8 sequence (a stream escapes those and keeps
// the rest for its next write).
std::size_t whole_utf8_prefix(std::string_view s);

// `s` in double quotes, as names and keys appear in messages: terminal_safe(), and cut
// to its first 200 bytes (with its length) when longer. Every message that quotes a user's text
// (a name, a key, a flag's value, a path) quotes it with this.
std::string in_quotes(std::string_view s);
// The same cut and escapes without the quotes (a parser's detail that echoes the input).
std::string shortened(std::string_view s);

// Shortest text that reads back as the same double ("0.5", "-1", "1e-12", "inf").
std::string format_number(double x);

// A JSON value with its place in a file. Cheap to copy; refers to the parsed document, which
// must outlive it. Every accessor checks the type and throws InputError at this node's path.
class JsonNode {
 public:
  // The document root (path "").
  JsonNode(const nlohmann::json& root, std::string source);

  const std::string& path() const { return path_; }
  const std::string& source() const { return source_; }
  const nlohmann::json& json() const { return *value_; }

  // Throws InputError(source, path, what).
  [[noreturn]] void fail(const std::string& what) const;

  // --- objects ---
  // Checks that this is an object and that every key is one of `allowed`; an unknown key names
  // the closest allowed one. Call it first, so that a misspelt key is reported as such rather
  // than as a missing one.
  void expect_object(std::initializer_list<std::string_view> allowed) const;
  void expect_object(std::span<const std::string_view> allowed) const;
  bool has(std::string_view key) const;
  // A required member: "missing required key" when absent.
  JsonNode at(std::string_view key) const;
  // An optional member.
  std::optional<JsonNode> find(std::string_view key) const;

  // --- arrays ---
  // Checks that this is an array and returns its length.
  std::size_t array_size() const;
  // Checks that this is an array of exactly `n` elements.
  void expect_array_size(std::size_t n) const;
  JsonNode element(std::size_t i) const;

  // --- scalars ---
  double number() const;  // finite
  int integer() const;    // a whole number within the range of int (5 and 5.0 both read as 5)
  bool boolean() const;
  std::string string() const;
  // The index in `names` of this string; `what` names the vocabulary in the message, e.g.
  // `unknown effect "frction"; did you mean "friction"?`.
  std::size_t choice(std::span<const std::string_view> names, std::string_view what) const;

  // Members with a fallback when absent (present but wrong is still an error).
  double number_or(std::string_view key, double fallback) const;
  int integer_or(std::string_view key, int fallback) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::string string_or(std::string_view key, std::string fallback) const;

 private:
  JsonNode(const nlohmann::json& value, std::string source, std::string path);
  JsonNode child(std::string_view key) const;
  [[noreturn]] void fail_type(std::string_view expected) const;

  const nlohmann::json* value_;
  std::string source_;
  std::string path_;
};

// --- readers for the value types that scenes and queries share ---

// Every vector is checked component by component for finiteness and magnitude before anything
// (a norm, a normalisation) is computed from it; the limits are in sim/limits.hpp.

// [x, y, z], each finite and at most `max_component` in magnitude (default: kMaxCoordinate).
Vec3 read_vec3(const JsonNode& node, double max_component);
Vec3 read_vec3(const JsonNode& node);
// [x, y, z] whose norm is at most `max_norm` (a velocity, gravity); `unit` for the message.
Vec3 read_bounded_vector(const JsonNode& node, double max_norm, std::string_view unit);
// [x, y, z], each in [min_half_extent, kMaxHalfExtent] (box half extents; the default minimum is
// a simulated box's, kMinHalfExtent); the error names the offending component.
Vec3 read_half_extents(const JsonNode& node, double min_half_extent = limits::kMinHalfExtent);
// [w, x, y, z], normalised; a zero quaternion is an error.
Quat read_orientation(const JsonNode& node);
// [x, y, z], normalised; a zero vector is an error.
Vec3 read_direction(const JsonNode& node);
// A number >= 0.
double read_non_negative(const JsonNode& node);
// A number > 0.
double read_positive(const JsonNode& node);
// A number in [lo, hi]; `unit` (may be empty) for the message.
double read_in_range(const JsonNode& node, double lo, double hi, std::string_view unit);
// A name: non-empty, not only white space or other invisible characters (non-breaking and
// zero-width spaces, joiners, a byte order mark), no control characters (C0 or C1; names are
// printed).
std::string read_name(const JsonNode& node);
// {"normal": [x, y, z], "offset": d}: both optional (default: the plane z = 0, solid below).
HalfSpace read_half_space(const JsonNode& node);

}  // namespace boxpile::json_input
