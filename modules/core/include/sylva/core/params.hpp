#pragma once
// Parameters are data (DESIGN.md §2). A settings struct lists its fields once, in visit():
//
//   struct ChunkLodSettings {
//     float max_pixel_error = 1.0f;
//     Criterion criterion = Criterion::kScreenSpace;
//     template <class V> void visit(V& v) {
//       v(max_pixel_error, "max_pixel_error", {.min = 0.05f, .max = 64.f, .unit = "px",
//         .help = "Largest allowed projected height error", .rebuild = sylva::Rebuild::kNone});
//       v(criterion, "criterion");
//     }
//   };
//
// From that one list this header derives: a flat list of descriptors (path, type, ParamInfo and a
// type-erased accessor: what the editor draws and the benchmark sweeps), set/get by dotted path
// from text (`--set terrain.max_pixel_error=2`), whole-struct validation and a diff that says what
// must be rebuilt. JSON load/save lives in <sylva/core/params_json.hpp> so that settings headers
// do not pull in nlohmann/json.
//
// Supported field types: bool, int (int32_t), uint32_t, int64_t, uint64_t, float, double,
// std::string, enums with names (see EnumName below), glm::vec<2..4> of float, double, int or
// uint32 (vec2/3/4, dvec2/3/4, ivec2/3/4, uvec2/3/4), and nested structs with their own visit()
// (path segments joined with '.'). Any other type is a compile error naming the field type.
//
// Rules every operation follows (tested in params_test / params_stability_test):
//  - A failed set (wrong type, out of range, NaN/Inf, unknown name) leaves the target unchanged.
//  - float and double parameters are always finite; NaN and Inf are rejected with a message.
//  - Integers must be exact: 2.5 or 99999999999 for an int32 is an error, never a truncation.
//  - Messages start with the full dotted path: "terrain.max_pixel_error: 100 is above the maximum 64".

#include <sylva/core/assert.hpp>
#include <sylva/core/result.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace sylva {

// What must be redone when a parameter changes at run time (DESIGN.md §2b). Ordered, so the
// largest value of a set of changes is what to do.
enum class Rebuild : std::uint8_t {
  kNone = 0,     // read every frame: nothing to rebuild
  kGpu = 1,      // GPU buffers/textures/shaders derived from the setting must be rebuilt
  kOffline = 2,  // offline data (chunk tree, impostor bake, world generation) must be rebuilt
};
const char* to_string(Rebuild rebuild);

// Metadata of one parameter: the third argument of the visitor. Designated initialisers must
// follow this declaration order (C++20): min, max, step, unit, help, rebuild, log_scale.
// min/max are doubles so int64/double ranges fit, and float literals (`.max = 64.f`) widen
// exactly. Bounds are inclusive and apply to every numeric component (vectors per component);
// for std::string they bound the length in bytes; bools and enums ignore them.
// unit and help must point at string literals (descriptors keep the pointers).
struct ParamInfo {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  double step = 0.0;        // editor drag speed / sweep step hint; 0 = let the tool choose
  const char* unit = "";    // "px", "m", "m/s", "deg", ... ("" = dimensionless)
  const char* help = "";    // one sentence for tooltips and generated docs
  Rebuild rebuild = Rebuild::kNone;
  bool log_scale = false;   // editor sliders and sweeps should step geometrically
};

// Enums are parameters when a function `enum_names(E)` is findable by argument-dependent lookup
// (declare it in the enum's namespace, or as a friend inside the struct that owns a nested enum).
// It returns any range of EnumName<E>; the names are what JSON files and --set use:
//
//   enum class Criterion { kScreenSpace, kDistance };
//   constexpr std::array<sylva::EnumName<Criterion>, 2> enum_names(Criterion) {
//     return {{{Criterion::kScreenSpace, "screen_space"}, {Criterion::kDistance, "distance"}}};
//   }
template <class E>
struct EnumName {
  E value;
  const char* name;
};

template <class E>
concept NamedEnum = std::is_enum_v<E> && requires { enum_names(E{}); };

// Type-erased view of an enum's names, built once per enum type.
struct EnumTable {
  std::vector<std::pair<std::int64_t, std::string>> entries;  // (value, name) in declared order
  std::size_t size = 0;                                      // sizeof(E)
  std::int64_t (*get)(const void* e) = nullptr;
  void (*set)(void* e, std::int64_t value) = nullptr;

  // The name of value, or nullptr when the value has no name.
  const char* name_of(std::int64_t value) const;
  // "a, b, c": for error messages and help.
  std::string joined_names() const;
};

template <NamedEnum E>
const EnumTable& enum_table() {
  static const EnumTable table = [] {
    EnumTable t;
    for (const auto& entry : enum_names(E{})) {
      const std::string name = entry.name;
      for (const auto& [v, n] : t.entries) {
        SYLVA_ASSERT(n != name, "enum name \"{}\" is listed twice", name);
        SYLVA_ASSERT(v != static_cast<std::int64_t>(entry.value),
                     "enum value {} has two names (\"{}\" and \"{}\")", v, n, name);
      }
      SYLVA_ASSERT(!name.empty(), "an enum name is empty");
      t.entries.emplace_back(static_cast<std::int64_t>(entry.value), name);
    }
    SYLVA_ASSERT(!t.entries.empty(), "enum_names() returned no names");
    t.size = sizeof(E);
    t.get = [](const void* e) { return static_cast<std::int64_t>(*static_cast<const E*>(e)); };
    t.set = [](void* e, std::int64_t value) { *static_cast<E*>(e) = static_cast<E>(value); };
    return t;
  }();
  return table;
}

// Scalar type of a parameter (of each component for vectors).
enum class ParamType : std::uint8_t { kBool, kInt32, kUInt32, kInt64, kUInt64, kFloat, kDouble, kString, kEnum };

// A typed pointer to one parameter (no ownership). components is 1 for scalars, 2..4 for glm vectors.
struct ParamRef {
  ParamType type = ParamType::kFloat;
  std::uint8_t components = 1;
  void* ptr = nullptr;
  const EnumTable* enum_table = nullptr;  // only for kEnum

  bool same_type(const ParamRef& other) const {
    return type == other.type && components == other.components && enum_table == other.enum_table;
  }
};

namespace detail {
template <class T> struct LeafTraits { static constexpr bool kSupported = false; };
template <class T, ParamType kType>
struct ScalarLeaf {
  static constexpr bool kSupported = true;
  static ParamRef ref(T& v) { return ParamRef{kType, 1, &v, nullptr}; }
};
template <> struct LeafTraits<bool> : ScalarLeaf<bool, ParamType::kBool> {};
template <> struct LeafTraits<std::int32_t> : ScalarLeaf<std::int32_t, ParamType::kInt32> {};
template <> struct LeafTraits<std::uint32_t> : ScalarLeaf<std::uint32_t, ParamType::kUInt32> {};
template <> struct LeafTraits<std::int64_t> : ScalarLeaf<std::int64_t, ParamType::kInt64> {};
template <> struct LeafTraits<std::uint64_t> : ScalarLeaf<std::uint64_t, ParamType::kUInt64> {};
template <> struct LeafTraits<float> : ScalarLeaf<float, ParamType::kFloat> {};
template <> struct LeafTraits<double> : ScalarLeaf<double, ParamType::kDouble> {};
template <> struct LeafTraits<std::string> : ScalarLeaf<std::string, ParamType::kString> {};

template <class C> constexpr bool kVecComponent =
    std::is_same_v<C, float> || std::is_same_v<C, double> || std::is_same_v<C, std::int32_t> ||
    std::is_same_v<C, std::uint32_t>;

template <glm::length_t L, class C, glm::qualifier Q>
  requires(L >= 2 && L <= 4 && kVecComponent<C>)
struct LeafTraits<glm::vec<L, C, Q>> {
  static constexpr bool kSupported = true;
  static ParamRef ref(glm::vec<L, C, Q>& v) {
    ParamRef r = LeafTraits<C>::ref(v[0]);  // glm stores components contiguously
    r.components = static_cast<std::uint8_t>(L);
    return r;
  }
};

// Asserts a visit() name is a usable path segment (non-empty, no '.', '[', ']', '=' or spaces).
void check_param_name(const char* name);
}  // namespace detail

template <class T>
concept ParamLeaf = detail::LeafTraits<T>::kSupported || NamedEnum<T>;

template <ParamLeaf T>
ParamRef make_param_ref(T& value) {
  if constexpr (NamedEnum<T>) {
    return ParamRef{ParamType::kEnum, 1, &value, &enum_table<T>()};
  } else {
    return detail::LeafTraits<T>::ref(value);
  }
}

// One parameter of a live settings object: what the editor draws a widget for and what a sweep
// sets. It is a handle (like a pointer): it stays valid while the object it was described from
// lives and is not moved, and the set functions write through it even on a const descriptor.
struct ParamDescriptor {
  std::string path;  // "terrain.lod.max_pixel_error"
  ParamInfo info;
  ParamRef ref;

  // "bool", "int32", "uint32", "int64", "uint64", "float", "double", "string", "enum",
  // "vec3", "dvec2", "ivec2", "uvec4", ...
  std::string type_name() const;

  // The value as text that set_string() accepts back unchanged: true/false, shortest
  // round-trip numbers ("0.1" for 0.1f), the raw string, the enum name, "x,y,z" for vectors.
  std::string get_string() const;

  // Parses text for this parameter's type (numbers, true/false/1/0/on/off/yes/no, enum names,
  // "x,y,z" or "[x, y, z]" for vectors, raw text for strings), validates it (range, finite)
  // and writes it. On failure the value is unchanged and the message names the path.
  Status set_string(std::string_view text) const;

  // Validates the current value (range, finite, named enum value).
  Status check() const;

  // Typed access for widgets; asserts T is exactly the parameter's type. Writing through the
  // reference bypasses validation: call check() afterwards (and revert on failure) or use set().
  template <ParamLeaf T>
  T& value() const {
    T probe{};
    SYLVA_ASSERT(make_param_ref(probe).same_type(ref), "{} is a {}, not the requested type", path, type_name());
    return *static_cast<T*>(ref.ptr);
  }

  // Typed, validated set; asserts T is exactly the parameter's type. Unchanged on failure.
  template <ParamLeaf T>
  Status set(const T& candidate) const {
    T copy = candidate;
    const ParamRef staged = make_param_ref(copy);
    SYLVA_ASSERT(staged.same_type(ref), "{} is a {}, not the type passed to set()", path, type_name());
    SYLVA_TRY(check_staged(staged));
    *static_cast<T*>(ref.ptr) = std::move(copy);
    return {};
  }

  // Whether two descriptors of the same parameter hold the same bits.
  bool same_value(const ParamDescriptor& other) const;

  // Validates a value of this parameter's type stored at staged.ptr (not yet written).
  Status check_staged(const ParamRef& staged) const;
};

class ParamCollector;

// A settings struct: has a template member visit(V&) listing its fields.
template <class T>
concept Visitable = requires(T& t, ParamCollector& c) { t.visit(c); };

// The visitor that turns visit() into descriptors. Nested Visitable fields recurse with their
// name appended to the path; leaves become descriptors.
class ParamCollector {
 public:
  ParamCollector(std::vector<ParamDescriptor>& out, std::string prefix)
      : out_(&out), prefix_(std::move(prefix)) {}

  // For a nested struct the info is accepted (e.g. for its help text) but not recorded.
  template <class T>
  void operator()(T& field, const char* name, const ParamInfo& info = {}) {
    detail::check_param_name(name);
    std::string path = prefix_.empty() ? std::string(name) : prefix_ + "." + name;
    if constexpr (Visitable<T>) {
      std::string saved = std::exchange(prefix_, std::move(path));
      field.visit(*this);
      prefix_ = std::move(saved);
    } else {
      static_assert(ParamLeaf<T>,
                    "unsupported parameter type: use bool, int32/uint32/int64/uint64, float, double, "
                    "std::string, an enum with enum_names(), a glm vec2..4, or a struct with visit()");
      out_->push_back(ParamDescriptor{std::move(path), info, make_param_ref(field)});
    }
  }

 private:
  std::vector<ParamDescriptor>* out_;
  std::string prefix_;
};

namespace detail {
// Asserts that no two descriptors share a path (a visit() listing a name twice).
void check_unique_paths(std::span<const ParamDescriptor> params);
}  // namespace detail

// Every parameter of obj, in visit() order, paths prefixed with "prefix." when prefix is given.
// The descriptors point into obj (see ParamDescriptor). For a const object use the result only
// to read (get_string, check); writing through it is undefined.
template <Visitable T>
std::vector<ParamDescriptor> describe_params(T& obj, std::string_view prefix = {}) {
  std::vector<ParamDescriptor> out;
  ParamCollector collector(out, std::string(prefix));
  obj.visit(collector);
  detail::check_unique_paths(out);
  return out;
}
template <Visitable T>
std::vector<ParamDescriptor> describe_params(const T& obj, std::string_view prefix = {}) {
  return describe_params(const_cast<T&>(obj), prefix);  // visit() is non-const but only reads
}

// --- operations on a list of descriptors (the non-template core; the overloads below on a
// settings object describe it and forward here) ---

// The descriptor whose path is exactly `path`. kNotFound names the path, suggests the nearest
// known path, or lists the parameters when `path` names a group ("terrain.lod").
Result<ParamDescriptor> find_param(std::span<const ParamDescriptor> params, std::string_view path);
// Parse + validate + write; unchanged on failure.
Status set_param(std::span<const ParamDescriptor> params, std::string_view path, std::string_view text);
Result<std::string> get_param(std::span<const ParamDescriptor> params, std::string_view path);
// Every violation (out of range, NaN/Inf, unnamed enum value), one message each, in visit() order.
std::vector<Error> param_violations(std::span<const ParamDescriptor> params);
// OK, or kInvalidArgument with all violations joined by newlines.
Status validate_params(std::span<const ParamDescriptor> params);

// Splits "terrain.max_pixel_error=2" at the first '='; the path must be non-empty.
Result<std::pair<std::string, std::string>> parse_param_assignment(std::string_view assignment);

// One parameter that differs between two states of the same settings.
struct ParamChange {
  std::string path;
  Rebuild rebuild = Rebuild::kNone;
};
// Parameters whose values differ (bitwise for numbers), in order; both lists must describe the
// same type (asserted).
std::vector<ParamChange> diff_params(std::span<const ParamDescriptor> before,
                                     std::span<const ParamDescriptor> after);
// The largest rebuild of a set of changes (kNone when empty).
Rebuild max_rebuild(std::span<const ParamChange> changes);

// --- the same operations on a settings object ---

template <Visitable T>
Status set_param(T& obj, std::string_view path, std::string_view text) {
  return set_param(describe_params(obj), path, text);
}
template <Visitable T>
Result<std::string> get_param(const T& obj, std::string_view path) {
  return get_param(describe_params(obj), path);
}
template <Visitable T>
Status validate_params(const T& obj, std::string_view prefix = {}) {
  return validate_params(describe_params(obj, prefix));
}
template <Visitable T>
std::vector<ParamChange> diff_params(const T& before, const T& after) {
  return diff_params(describe_params(before), describe_params(after));
}

// Named settings sections composed at run time: the scene registers each module's settings
// ("terrain" -> TerrainSettings&) so `--set terrain.max_pixel_error=2`, the editor and the
// benchmark address all of them by path. The registry does not own the sections; each must
// outlive it (or be removed first).
class ParamRegistry {
 public:
  using VisitFn = std::function<void(ParamCollector&)>;

  template <Visitable T>
  void add(std::string_view name, T& section) {
    add_section(name, [&section](ParamCollector& c) { section.visit(c); });
  }
  // Asserts the name is a valid path segment and not registered yet.
  void add_section(std::string_view name, VisitFn visit);
  bool remove(std::string_view name);
  bool contains(std::string_view name) const;
  std::vector<std::string> section_names() const;

  // Every parameter of every section, paths "<section>.<field>...", sections in insertion order.
  std::vector<ParamDescriptor> describe() const;
  Result<ParamDescriptor> find(std::string_view path) const;
  Status set(std::string_view path, std::string_view text) const;
  // "path=value", the form of the command line's --set.
  Status set_assignment(std::string_view assignment) const;
  Result<std::string> get(std::string_view path) const;
  Status validate() const;

 private:
  struct Section {
    std::string name;
    VisitFn visit;
  };
  std::vector<Section> sections_;
};

}  // namespace sylva
