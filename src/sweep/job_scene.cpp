#include "tumble/job_scene.hpp"

#include <optional>
#include <tuple>

#include "toml_text.hpp"

namespace tumble::sweep {
namespace {

namespace fs = std::filesystem;

// The path's segments below the scene's root table: ("floor", "restitution") or, for a body,
// the body's table and ("orientation", "degrees").
struct Target {
  toml::table* table = nullptr;   // where the first key of `keys` lives
  std::vector<std::string> keys;  // the rest of the path, the last one set
};

std::vector<std::string> split(std::string_view s) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t dot; (dot = s.find('.', start)) != std::string_view::npos; start = dot + 1)
    parts.emplace_back(s.substr(start, dot - start));
  parts.emplace_back(s.substr(start));
  return parts;
}

// The body table named `rest`'s leading name, longest name first (a name may hold dots).
Target find_body(toml::table& root, const std::string& rest) {
  Target best;
  std::size_t best_length = 0;
  toml::array* bodies = root["body"].as_array();
  if (!bodies) return best;
  for (std::size_t i = 0; i < bodies->size(); ++i) {
    toml::table* body = (*bodies)[i].as_table();
    if (!body) continue;
    const std::string name =
        (*body)["name"].value<std::string>().value_or("body" + std::to_string(i + 1));
    if (rest.size() > name.size() + 1 && rest.starts_with(name) && rest[name.size()] == '.' &&
        name.size() >= best_length) {
      best = {body, split(std::string_view(rest).substr(name.size() + 1))};
      best_length = name.size();
    }
  }
  return best;
}

Target find_target(toml::table& root, const Parameter& p) {
  const std::string& path = p.key->path;
  const std::size_t dot = path.find('.');
  const std::string table = path.substr(0, dot);
  if (table == "body") {
    Target t = find_body(root, path.substr(dot + 1));
    if (!t.table) fail(p.key->key_at, "key path \"" + path + "\" names no body of the scene");
    return t;
  }
  if (!root.contains(table)) root.insert(table, toml::table{});
  toml::table* t = root[table].as_table();
  if (!t)
    fail(p.key->key_at, "key path \"" + path + "\": " + table + " is not a table in the scene");
  return {t, split(std::string_view(path).substr(dot + 1))};
}

// Sets the parameter's value at its key path, making the tables on the way where the scene has
// none (a [floor] that the scene leaves out, a body's orientation).
void apply(toml::table& root, const Parameter& p) {
  Target t = find_target(root, p);
  toml::table* table = t.table;
  for (std::size_t i = 0; i + 1 < t.keys.size(); ++i) {
    if (!table->contains(t.keys[i])) table->insert(t.keys[i], toml::table{});
    toml::table* next = (*table)[t.keys[i]].as_table();
    if (!next)
      fail(p.key->key_at, "key path \"" + p.key->path + "\": " + t.keys[i] +
                              " is not a table in the scene, so it has no key " + t.keys[i + 1]);
    table = next;
  }
  toml::table holder;
  const auto value = parse_value(p.value, holder);
  table->insert_or_assign(t.keys.back(), *value.node());
}

// Relative mesh paths are relative to the base scene; the effective scene lies elsewhere.
void absolute_meshes(toml::table& root, const fs::path& scene_path) {
  toml::array* bodies = root["body"].as_array();
  if (!bodies) return;
  for (toml::node& element : *bodies) {
    toml::table* body = element.as_table();
    if (!body) continue;
    const std::optional<std::string> mesh = (*body)["mesh"].value<std::string>();
    if (!mesh || mesh->empty()) continue;
    const fs::path p(*mesh);
    if (p.is_absolute()) continue;
    body->insert_or_assign("mesh",
                           fs::absolute(scene_path.parent_path() / p).lexically_normal().string());
  }
}

std::string header(const Plan& plan, const Job& job) {
  std::string h = "# tumble sweep, " + job_folder_name(job.index) + ": tumble " + plan.command;
  for (const std::string& arg : plan.args) h += " " + arg;  // the options decide the outputs too
  // A comment ends at a line break: one inside an argument would make the rest TOML.
  for (char& c : h)
    if (c == '\n' || c == '\r') c = ' ';
  h += "\n";
  for (const Parameter& p : job.parameters) h += "# " + p.key->path + " = " + p.value + "\n";
  return h + "\n";
}

std::string scene_text(const Plan& plan, const Job& job, const std::vector<Parameter>& params) {
  toml::table root = toml::parse(plan.scene_text, plan.scene_path.string());
  for (const Parameter& p : params) apply(root, p);
  absolute_meshes(root, plan.scene_path);
  return header(plan, job) + toml_document(root);
}

// Where the node that `p` set lies in `text` (its key, and its value's first and last
// character), found by parsing the text again.
struct Placed {
  toml::source_region key, value;
};
std::optional<Placed> placed(const std::string& text, const Parameter& p) {
  toml::table root;
  try {
    root = toml::parse(text);
  } catch (const toml::parse_error&) {
    return std::nullopt;
  }
  Target t = find_target(root, p);
  toml::table* table = t.table;
  for (std::size_t i = 0; table && i + 1 < t.keys.size(); ++i)
    table = (*table)[t.keys[i]].as_table();
  if (!table) return std::nullopt;
  for (auto&& [key, node] : *table)
    if (key.str() == t.keys.back()) return Placed{key.source(), node.source()};
  return std::nullopt;
}

bool inside(const SourceLocation& at, const toml::source_region& r) {
  const auto pos = std::tuple(at.line, at.column);
  return std::tuple(static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)) <= pos &&
         pos <= std::tuple(static_cast<int>(r.end.line), static_cast<int>(r.end.column));
}

std::string describe_job(const Job& job) {
  std::string s = "job " + std::to_string(job.index);
  std::string values;
  for (const Parameter& p : job.parameters)
    values += (values.empty() ? "" : ", ") + p.key->path + " = " + p.value;
  return values.empty() ? s : s + " (" + values + ")";
}

}  // namespace

std::string job_scene_text(const Plan& plan, const Job& job) {
  return scene_text(plan, job, job.parameters);
}

namespace {

// Checks `job`'s scene (named `name` in the loader's errors) with `check`; `who` says which job
// or value it is in an error's message.
void check_scene(const Plan& plan, const Job& job, const SceneCheck& check, const std::string& name,
                 const std::string& who) {
  const std::string text = job_scene_text(plan, job);  // its own errors point into the plan
  try {
    check(text, name);
    return;
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::BadInput) throw;
    const std::string what = who + ": " + e.what();
    // Not about the scene text (the command's overrides: --duration against the scene's dt):
    // the plan's args.
    if (e.where().file.empty()) fail(plan.args_at, what);
    // Not about the scene text but a file it names (a mesh): where the loader says.
    if (e.where().file != name) fail(e.where(), what);
  }
  // The scene rejects the job: find the one parameter that it rejects alone, and say whether
  // its value (the loader points inside it) or its key (unknown, or a table it lacks) is wrong.
  for (const Parameter& p : job.parameters) {
    const std::string alone = scene_text(plan, job, {p});
    try {
      check(alone, name);
    } catch (const Error& e) {
      if (e.kind() != ErrorKind::BadInput || e.where().file != name) continue;
      const std::optional<Placed> at = placed(alone, p);
      const bool value = at && inside(e.where(), at->value) && !inside(e.where(), at->key);
      fail(value ? p.from : p.key->key_at,
           who + ": " + e.what() + (value ? "" : " (key path \"" + p.key->path + "\")"));
    }
  }
  // Only the combination fails (dt against duration, a body inside the floor): the first key.
  try {
    check(text, name);
  } catch (const Error& e) {
    fail(job.parameters.empty() ? plan.scene_at : job.parameters.front().key->key_at,
         who + ": " + e.what());
  }
}

// The ends of a random key's range as TOML text (uniform and integer: both ends; choice: every
// value); a normal distribution has none (its draws are checked job by job).
std::vector<std::string> range_ends(const Distribution& d) {
  using Kind = Distribution::Kind;
  switch (d.kind) {
    case Kind::Integer:
      return {std::to_string(d.lo), std::to_string(d.hi)};
    case Kind::Choice:
      return d.choices;
    case Kind::Normal:
      return {};
    case Kind::Uniform:
      break;
  }
  std::vector<std::string> ends;
  for (const std::vector<double>* end : {&d.first, &d.second}) {
    std::string text;
    for (std::size_t i = 0; i < end->size(); ++i) text += (i ? ", " : "") + toml_number((*end)[i]);
    ends.push_back(d.vector ? "[" + text + "]" : text);
  }
  return ends;
}

}  // namespace

void check_job_scene(const Plan& plan, const Job& job, const SceneCheck& check) {
  check_scene(plan, job, check, job_folder_name(job.index) + "/scene.toml", describe_job(job));
}

void check_plan_values(const Plan& plan, const SceneCheck& check) {
  const std::size_t count = plan.random_count.value_or(1);
  // Each random key at the ends of its range, the other keys as job 0 has them: an end the
  // scene rejects is the distribution's fault, said before any job's draw shows it.
  const Job first = make_job(plan, 0);
  for (std::size_t k = 0; k < plan.random.size(); ++k) {
    const std::size_t at = plan.grid.size() + k;  // keys(): grid first, then random
    for (const std::string& end : range_ends(plan.random[k].distribution)) {
      Job job = first;
      job.parameters[at].value = end;
      const std::string who =
          "the plan's " + job.parameters[at].key->path + " at the end of its range (" + end + ")";
      check_scene(plan, job, check, "plan-check/scene.toml", who);
    }
  }
  // Job 0, and for each grid value the first job that has it (the other axes at their first).
  check_job_scene(plan, first, check);
  std::size_t stride = count;  // jobs between two values of the axis
  for (std::size_t a = plan.grid.size(); a-- > 0;) {
    for (std::size_t v = 1; v < plan.grid[a].values.size(); ++v)
      check_job_scene(plan, make_job(plan, v * stride), check);
    stride *= plan.grid[a].values.size();
  }
}

}  // namespace tumble::sweep
