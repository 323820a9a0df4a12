// Parsing a sweep plan: its keys, the scene it names, the grid and the distributions, each error
// at its place in the plan. Whether a key path names a scene key the scene accepts, and whether
// each value is one the scene accepts, is left to the scene loader (job_scene.cpp): one source of
// truth for what a scene may say.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <span>
#include <system_error>
#include <tuple>

#include "toml_text.hpp"
#include "tumble/scene.hpp"
#include "tumble/sweep.hpp"

namespace tumble::sweep {
namespace {

namespace fs = std::filesystem;

std::string in_quotes(std::string_view s) {
  return '"' + std::string(s) + '"';
}

std::string did_you_mean(std::string_view word, const std::vector<std::string_view>& known) {
  const auto match = closest_match(word, known);
  return match ? " (did you mean " + in_quotes(*match) + "?)" : "";
}

constexpr std::array<std::string_view, 5> kPlanKeys = {"scene", "command", "args", "grid",
                                                       "random"};
constexpr std::array<std::string_view, 6> kSceneTables = {"simulation", "floor", "render",
                                                          "camera",     "light", "body"};
constexpr std::array<std::string_view, 4> kDistributions = {"uniform", "normal", "integer",
                                                            "choice"};
// More jobs than this is a typo in a grid, not a sweep anyone runs (and job numbers stay sane).
constexpr std::size_t kMaxJobs = 100'000'000;

std::vector<std::string_view> names(std::span<const std::string_view> list) {
  return {list.begin(), list.end()};
}

auto position(const toml::source_position& p) {
  return std::tuple(p.line, p.column);
}

// A plan being read: its file name for locations, the base scene's body names for key paths.
struct Reader {
  std::string file;
  std::vector<std::string> body_names;
  Plan& plan;

  SourceLocation at(const toml::node& node) const { return location(node, file); }
  SourceLocation at(const toml::key& key) const { return location(key.source().begin, file); }

  // The keys of `table` in the order the plan writes them (toml++ sorts them by name).
  std::vector<std::pair<const toml::key*, const toml::node*>> in_file_order(
      const toml::table& table) const {
    std::vector<std::pair<const toml::key*, const toml::node*>> entries;
    for (auto&& [key, node] : table) entries.emplace_back(&key, &node);
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
      return position(a.first->source().begin) < position(b.first->source().begin);
    });
    return entries;
  }

  // Checks the shape of a key path against the scene: a table the scene has, a body it names,
  // and a key after them. Which keys a table takes is the scene loader's to say.
  void check_path(const std::string& path, const SourceLocation& where) const {
    const std::size_t dot = path.find('.');
    const std::string table = path.substr(0, dot);
    if (std::find(kSceneTables.begin(), kSceneTables.end(), table) == kSceneTables.end())
      fail(where, "unknown key path " + in_quotes(path) + ": a scene has no table " +
                      in_quotes(table) + did_you_mean(table, names(kSceneTables)) +
                      " (a key path is table.key or body.<name>.key)");
    if (dot == std::string::npos || dot + 1 == path.size())
      fail(where, "key path " + in_quotes(path) + " needs a key after " + in_quotes(table));
    if (table != "body") return;
    const std::string rest = path.substr(dot + 1);
    for (const std::string& name : body_names)
      if (rest.size() > name.size() + 1 && rest.starts_with(name) && rest[name.size()] == '.')
        return;
    const std::string name = rest.substr(0, rest.find('.'));
    std::vector<std::string_view> known(body_names.begin(), body_names.end());
    if (std::find(body_names.begin(), body_names.end(), rest) != body_names.end())
      fail(where, "key path " + in_quotes(path) + " needs a key after the body's name");
    fail(where, "unknown key path " + in_quotes(path) + ": the scene has no body named " +
                    in_quotes(name) + did_you_mean(name, known));
  }

  void add_key(PlanKey key) {
    for (const PlanKey* other : plan.keys())
      if (other->path == key.path)
        fail(key.key_at, "key path " + in_quotes(key.path) +
                             " is set twice in the plan (first at " +
                             std::to_string(other->key_at.line) + ":" +
                             std::to_string(other->key_at.column) + ")");
    check_path(key.path, key.key_at);
  }

  // [grid]: each key path (quoted, or written as dotted keys) takes an array of values.
  void read_grid(const toml::table& table, const std::string& prefix) {
    for (const auto& [key, node] : in_file_order(table)) {
      const std::string path = prefix + std::string(key->str());
      if (node->is_table()) {
        read_grid(*node->as_table(), path + ".");
        continue;
      }
      const toml::array* values = node->as_array();
      if (!values)
        fail(at(*node), "[grid] " + in_quotes(path) +
                            " must be an array of the values it takes, e.g. [0.2, 0.5, 0.8]");
      if (values->empty()) fail(at(*node), "[grid] " + in_quotes(path) + " has no values");
      GridAxis axis;
      axis.key = {path, at(*key), at(*node)};
      add_key(axis.key);
      for (const toml::node& value : *values) {
        axis.values.push_back(toml_text(value));
        axis.value_at.push_back(at(value));
      }
      plan.grid.push_back(std::move(axis));
    }
  }

  double number(const toml::node& node, const std::string& what) const {
    if (!node.is_number()) fail(at(node), what + " must be a number, got " + toml_text(node));
    const double x = node.is_integer() ? static_cast<double>(node.as_integer()->get())
                                       : node.as_floating_point()->get();
    if (!std::isfinite(x)) fail(at(node), what + " must be finite");
    return x;
  }

  // The two parameters of uniform or normal: two numbers, or two arrays of as many numbers.
  void read_pair(const toml::array& pair, Distribution& d, const std::string& what) const {
    const bool vectors = pair[0].is_array() || pair[1].is_array();
    if (!vectors) {
      d.first = {number(pair[0], what + "'s first value")};
      d.second = {number(pair[1], what + "'s second value")};
      return;
    }
    const toml::array* a = pair[0].as_array();
    const toml::array* b = pair[1].as_array();
    if (!a || !b || a->size() != b->size() || a->empty())
      fail(at(pair), what +
                         " of a vector takes two arrays of equal length, e.g. [[0.0, 0.0, 1.0], "
                         "[0.0, 0.0, 4.0]]");
    d.vector = true;
    for (std::size_t i = 0; i < a->size(); ++i) {
      d.first.push_back(number((*a)[i], what + "'s first array"));
      d.second.push_back(number((*b)[i], what + "'s second array"));
    }
  }

  Distribution read_distribution(const toml::table& table, const std::string& path) const {
    const std::string what = "[random] " + in_quotes(path);
    if (table.size() != 1)
      fail(at(table), what +
                          " must be one distribution: { uniform = [a, b] }, "
                          "{ normal = [mean, sd] }, { integer = [a, b] } or { choice = [...] }");
    // toml++'s iterator owns the pair it yields: take the references out while it lives.
    const auto entry = table.begin();
    const toml::key& key = entry->first;
    const toml::node& node = entry->second;
    const std::string name(key.str());
    const auto it = std::find(kDistributions.begin(), kDistributions.end(), name);
    if (it == kDistributions.end())
      fail(at(key), "unknown distribution " + in_quotes(name) + " in " + what +
                        did_you_mean(name, names(kDistributions)) +
                        " (expected one of: uniform, normal, integer, choice)");
    Distribution d;
    d.kind = static_cast<Distribution::Kind>(it - kDistributions.begin());
    const toml::array* values = node.as_array();
    const std::string label = what + " " + name;
    if (!values) fail(at(node), label + " takes an array, e.g. " + name + " = [0.0, 1.0]");
    if (d.kind == Distribution::Kind::Choice) {
      if (values->empty()) fail(at(node), label + " needs at least one value");
      for (const toml::node& value : *values) d.choices.push_back(toml_text(value));
      return d;
    }
    if (values->size() != 2)
      fail(at(node), label + " takes two values, got " + std::to_string(values->size()));
    if (d.kind == Distribution::Kind::Integer) {
      for (const toml::node& value : *values)
        if (!value.is_integer())
          fail(at(value), label + " takes two integers, got " + toml_text(value));
      d.lo = (*values)[0].as_integer()->get();
      d.hi = (*values)[1].as_integer()->get();
      if (d.lo > d.hi) fail(at(node), label + " must run upwards: [a, b] with a <= b");
      return d;
    }
    read_pair(*values, d, label);
    for (std::size_t i = 0; i < d.first.size(); ++i) {
      if (d.kind == Distribution::Kind::Uniform && d.first[i] > d.second[i])
        fail(at(node), label + " must run upwards: [a, b] with a <= b");
      if (d.kind == Distribution::Kind::Normal && d.second[i] < 0.0)
        fail(at(node), label + "'s standard deviation must be >= 0");
    }
    return d;
  }

  // A table under [random] is a distribution when one of its keys is not itself a table;
  // otherwise it groups dotted key paths (`floor.restitution = { uniform = ... }` unquoted).
  void read_random(const toml::table& table, const std::string& prefix) {
    for (const auto& [key, node] : in_file_order(table)) {
      const std::string name(key->str());
      if (prefix.empty() && (name == "count" || name == "seed")) continue;
      const std::string path = prefix + name;
      const toml::table* t = node->as_table();
      if (!t)
        fail(at(*node), "[random] " + in_quotes(path) +
                            " must be a distribution, e.g. { uniform = [0.0, 1.0] }");
      const bool group = !t->empty() && std::all_of(t->begin(), t->end(), [](auto&& entry) {
        return entry.second.is_table();
      });
      if (group) {
        read_random(*t, path + ".");
        continue;
      }
      RandomKey r;
      r.key = {path, at(*key), at(*node)};
      add_key(r.key);
      r.distribution = read_distribution(*t, path);
      plan.random.push_back(std::move(r));
    }
  }

  void read_random_block(const toml::table& table) {
    plan.random_at = at(table);
    const toml::node* count = table.get("count");
    if (!count) fail(at(table), "[random] needs count, the number of draws (per grid point)");
    if (!count->is_integer() || count->as_integer()->get() < 1)
      fail(at(*count), "count in [random] must be an integer >= 1, got " + toml_text(*count));
    plan.random_count = static_cast<std::size_t>(count->as_integer()->get());
    const toml::node* seed = table.get("seed");
    if (!seed)
      fail(at(table), "[random] needs seed, an integer >= 0 (the same seed, the same jobs)");
    if (!seed->is_integer() || seed->as_integer()->get() < 0)
      fail(at(*seed), "seed in [random] must be an integer >= 0, got " + toml_text(*seed));
    plan.seed = static_cast<std::uint64_t>(seed->as_integer()->get());
    read_random(table, "");
  }
};

toml::table parse_toml(std::string_view text, const std::string& file) {
  try {
    return toml::parse(text, std::string_view(file));
  } catch (const toml::parse_error& e) {
    fail(location(e.source().begin, file), "TOML syntax error: " + std::string(e.description()));
  }
}

std::string read_text(const fs::path& path, const std::string& what, const SourceLocation& at) {
  std::error_code ec;
  if (fs::is_directory(path, ec))
    fail(at, "cannot read " + what + " " + in_quotes(path.string()) + ": it is a directory");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    fail(at, "cannot read " + what + " " + in_quotes(path.string()) + ": " +
                 (errno ? std::generic_category().message(errno) : "cannot open it"));
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) fail(at, "cannot read " + what + " " + in_quotes(path.string()) + ": read failed");
  return text;
}

// The names of the base scene's bodies as the scene loader gives them (unnamed: body<N>).
std::vector<std::string> body_names(const std::string& text, const std::string& file) {
  std::vector<std::string> found;
  const toml::table root = parse_toml(text, file);
  const toml::array* bodies = root["body"].as_array();
  if (!bodies) return found;
  for (std::size_t i = 0; i < bodies->size(); ++i) {
    const toml::table* body = (*bodies)[i].as_table();
    const std::optional<std::string> name =
        body ? (*body)["name"].value<std::string>() : std::nullopt;
    found.push_back(name.value_or("body" + std::to_string(i + 1)));
  }
  return found;
}

}  // namespace

std::size_t Plan::job_count() const {
  std::size_t n = random_count.value_or(1);
  for (const GridAxis& axis : grid) n *= axis.values.size();
  return n;
}

std::vector<const PlanKey*> Plan::keys() const {
  std::vector<const PlanKey*> keys;
  for (const GridAxis& axis : grid) keys.push_back(&axis.key);
  for (const RandomKey& r : random) keys.push_back(&r.key);
  return keys;
}

Plan parse_plan(std::string_view text, const std::string& path) {
  const toml::table root = parse_toml(text, path);
  Plan plan;
  plan.path = path;
  plan.stem = fs::path(path).stem().string();
  Reader reader{path, {}, plan};
  const SourceLocation top{path, 1, 1};

  std::vector<std::string_view> known = names(kPlanKeys);
  for (const auto& [key, node] : reader.in_file_order(root))
    if (std::find(known.begin(), known.end(), key->str()) == known.end())
      fail(reader.at(*key), "unknown key " + in_quotes(key->str()) + " in a sweep plan" +
                                did_you_mean(key->str(), known) +
                                " (a plan has scene, command, args, [grid] and [random])");

  const toml::node* scene = root.get("scene");
  if (!scene || !scene->is_string() || scene->as_string()->get().empty())
    fail(scene ? reader.at(*scene) : top,
         "a plan needs scene = \"FILE.toml\", the base scene (relative to the plan)");
  plan.scene_at = reader.at(*scene);
  const fs::path scene_path(scene->as_string()->get());
  plan.scene_path =
      scene_path.is_absolute() ? scene_path : fs::path(path).parent_path() / scene_path;
  plan.scene_text = read_text(plan.scene_path, "scene file", plan.scene_at);
  reader.body_names = body_names(plan.scene_text, plan.scene_path.string());

  plan.command = "render";
  plan.command_at = top;
  if (const toml::node* command = root.get("command")) {
    plan.command_at = reader.at(*command);
    const std::optional<std::string> name = command->value<std::string>();
    if (!name || (*name != "render" && *name != "simulate"))
      fail(plan.command_at,
           "command must be \"render\" or \"simulate\", got " + toml_text(*command));
    plan.command = *name;
  }

  plan.args_at = top;
  if (const toml::node* args = root.get("args")) {
    plan.args_at = reader.at(*args);
    const toml::array* list = args->as_array();
    if (!list)
      fail(plan.args_at, "args must be an array of strings, e.g. [\"--size\", \"320x240\"]");
    for (const toml::node& arg : *list) {
      if (!arg.is_string())
        fail(reader.at(arg), "args must be an array of strings; got " + toml_text(arg) +
                                 " (write numbers in quotes: \"1.0\")");
      plan.args.push_back(arg.as_string()->get());
    }
  }

  if (const toml::node* grid = root.get("grid")) {
    if (!grid->is_table()) fail(reader.at(*grid), "grid must be a table, written [grid]");
    reader.read_grid(*grid->as_table(), "");
  }
  if (const toml::node* random = root.get("random")) {
    if (!random->is_table()) fail(reader.at(*random), "random must be a table, written [random]");
    reader.read_random_block(*random->as_table());
  }
  if (plan.grid.empty() && !plan.random_count)
    fail(top, "a plan needs a [grid] of values or a [random] block (or both)");

  // The product, checked as it grows so it cannot overflow.
  std::size_t jobs = plan.random_count.value_or(1);
  if (jobs > kMaxJobs) fail(plan.random_at, "more than 1e8 jobs: is count a typo?");
  for (const GridAxis& axis : plan.grid) {
    jobs *= axis.values.size();
    if (jobs > kMaxJobs) fail(axis.key.key_at, "the grid gives more than 1e8 jobs");
  }
  return plan;
}

Plan load_plan(const fs::path& path) {
  return parse_plan(read_text(path, "sweep plan", {}), path.string());
}

}  // namespace tumble::sweep
