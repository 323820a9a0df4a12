#include "tumble/run_report.hpp"

#include <nlohmann/json.hpp>

#include "tumble/atomic_file.hpp"
#include "tumble/sha256.hpp"

namespace tumble {
namespace {

using nlohmann::ordered_json;

ordered_json vec(const Vec3& v) {
  return ordered_json::array({v.x(), v.y(), v.z()});
}

ordered_json settings_json(const Scene& s, const World* world) {
  ordered_json j;
  const SimulationSettings& sim = s.simulation;
  const bool adaptive = sim.integrator == Integrator::Adaptive;
  j["simulation"] = {
      {"duration_s", sim.duration_s},
      {"dt_s", sim.dt_s},
      {"integrator", to_string(sim.integrator)},
      {"tolerance", adaptive ? ordered_json(sim.tolerance) : ordered_json()},
      // The effective largest step (the scene's, or the sample interval); null: not adaptive.
      {"max_step_s", adaptive && world ? ordered_json(world->def().dt_s) : ordered_json()},
      {"rotation", to_string(sim.rotation)},
      {"gravity", vec(sim.gravity)},
      {"linear_drag", sim.linear_drag},
      {"angular_drag", sim.angular_drag}};
  if (s.floor)
    j["floor"] = {{"height", s.floor->height},
                  {"restitution", s.floor->restitution},
                  {"friction", s.floor->friction}};
  else
    j["floor"] = nullptr;
  j["render"] = {{"fps", s.render.fps},
                 {"width", s.render.width},
                 {"height", s.render.height},
                 {"antialias", kAntialiasNames[static_cast<int>(s.render.antialias)]},
                 {"msaa", s.render.msaa},
                 {"background", to_string(s.render.background)}};
  j["camera"] = {{"position", vec(s.camera.position)},
                 {"target", vec(s.camera.target)},
                 {"up", vec(s.camera.up)},
                 {"fov_deg", s.camera.fov_deg},
                 {"projection", kProjectionNames[static_cast<int>(s.camera.projection)]},
                 {"ortho_height", s.camera.ortho_height_m},
                 {"follow", s.camera.follow ? ordered_json(*s.camera.follow) : ordered_json()},
                 {"framed", s.camera.framed}};
  j["light"] = {{"direction", vec(s.light.direction)}, {"shadows", s.light.shadows}};
  return j;
}

ordered_json animation_json(const std::optional<FigureFacts::Animation>& a, const char* unit) {
  if (!a) return nullptr;
  return {{"frames", a->frames},   {"frame_step", a->frame_step},
          {"rate_hz", a->rate_hz}, {std::string("delays_") + unit, a->delays},
          {"exact", a->exact},     {"duration_s", a->duration_s}};
}

ordered_json figures_json(const FigureFacts& f) {
  ordered_json j;
  j["transparent"] = f.transparent;
  j["strobe"] = f.strobe_times_s.empty() ? ordered_json()
                                         : ordered_json{{"poses", f.strobe_times_s.size()},
                                                        {"times_s", f.strobe_times_s},
                                                        {"opacities", f.strobe_opacities}};
  j["gif"] = animation_json(f.gif, "cs");
  j["webp"] = animation_json(f.webp, "ms");
  return j;
}

}  // namespace

void write_run_report(const std::filesystem::path& path, const RunReport& r) {
  ordered_json j;
  j["tool"] = {{"name", "tumble"}, {"version", TUMBLE_VERSION}};
  j["command"] = r.command;
  if (r.scene) {
    j["scene"] = {{"path", r.scene->source_name}, {"sha256", sha256_hex(r.scene->source_text)}};
    j["settings"] = settings_json(*r.scene, r.world);
  }
  j["counts"] = {{"steps", r.steps},
                 {"derivative_evaluations", r.world ? r.world->derivative_evaluations() : 0},
                 {"samples", r.samples},
                 {"sample_rate_hz", r.sample_rate_hz},
                 {"every_step", r.every_step},
                 {"impacts", r.contact.impacts}};
  if (r.frames) j["counts"]["frames"] = *r.frames;
  if (r.frames_reused) j["counts"]["frames_reused"] = *r.frames_reused;
  if (r.world && r.world->def().integrator == Integrator::Adaptive) {
    const StepStats& st = r.world->step_stats();
    j["adaptive"] = {{"tolerance", r.world->def().tolerance},
                     {"first_step_s", r.world->def().first_step_s},
                     {"largest_step_s", r.world->def().dt_s},
                     {"accepted_steps", st.accepted},
                     {"rejected_steps", st.rejected},
                     {"smallest_step_taken_s", st.smallest_step_s},
                     {"largest_step_taken_s", st.largest_step_s}};
  }
  j["gl"] = r.gl_renderer.empty() ? ordered_json()
                                  : ordered_json{{"vendor", r.gl_vendor},
                                                 {"renderer", r.gl_renderer},
                                                 {"antialias", r.antialias_used}};
  j["encoder"] = r.encoder.empty() ? ordered_json() : ordered_json(r.encoder);
  ordered_json times;
  auto stage = [&](const char* name, const std::optional<double>& s) {
    if (s) times[name] = *s;
  };
  stage("framing_s", r.times.framing_s);
  stage("simulate_s", r.times.simulate_s);
  stage("render_s", r.times.render_s);
  stage("readback_s", r.times.readback_s);
  stage("encode_s", r.times.encode_s);
  stage("png_s", r.times.png_s);
  stage("gif_s", r.times.gif_s);
  stage("webp_s", r.times.webp_s);
  times["total_s"] = r.times.total_s;
  j["wall_time"] = times;
  j["physics"] = {{"energy_start_J", r.energy_start_J},
                  {"energy_end_J", r.energy_end_J},
                  {"max_contact_energy_gain_J", r.contact.max_energy_gain_J},
                  {"contacts", r.contact.impacts},
                  {"deepest_penetration_m", r.contact.deepest_penetration_m}};
  // Every pair that touched, "floor" as a name.
  ordered_json pairs = ordered_json::array();
  if (r.world)
    for (const PairContactStats& p : r.contact.pairs) {
      auto name = [&](int body) {
        return body == kFloorBody ? std::string("floor") : r.world->bodies()[body].name();
      };
      pairs.push_back({{"bodies", ordered_json::array({name(p.a), name(p.b)})},
                       {"impacts", p.impacts},
                       {"first_impact_t_s", p.impacts > 0 ? ordered_json(p.first_impact_t_s)
                                                           : ordered_json()},
                       {"deepest_penetration_m", p.deepest_penetration_m}});
    }
  j["physics"]["contact_pairs"] = pairs;
  ordered_json diagnostics = ordered_json::array();
  if (r.world)
    for (const Diagnostic& d : r.world->diagnostics().list())
      diagnostics.push_back({{"code", d.code},
                             {"severity", d.severity},
                             {"message", d.message},
                             {"t_s", d.t_s},
                             {"fix", d.fix},
                             {"occurrences", d.occurrences}});
  j["diagnostics"] = diagnostics;
  if (r.figures) j["figures"] = figures_json(*r.figures);
  ordered_json outputs = ordered_json::array();
  for (const auto& p : r.outputs)
    outputs.push_back(
        {{"path", p.string()},
         {"sha256", sha256_file_hex(r.staged_in ? r.staged_in->staged_path_of(p) : p)}});
  j["outputs"] = outputs;
  ordered_json bodies = ordered_json::array();
  if (r.world)
    for (std::size_t i = 0; i < r.world->bodies().size(); ++i) {
      const RigidBody& b = r.world->bodies()[i];
      const MeshBody* model = r.models ? r.models->model(i) : nullptr;
      const std::string shape = model           ? "mesh"
                                : b.is_particle() ? "particle"
                                : b.is_sphere()   ? "sphere"
                                                  : "box";
      ordered_json body = {{"name", b.name()},
                           {"shape", shape},
                           {"mass_kg", b.mass()},
                           {"com_offset_m", vec(b.com_offset())},
                           {"principal_moments_kg_m2", vec(b.inertia_body())}};
      if (model) {
        const Mat3 axes = b.principal_axes().toRotationMatrix();
        body["mesh"] = {
            {"path", r.scene ? r.scene->bodies[i].mesh : std::string()},
            {"volume_m3", model->mass.volume},
            {"principal_axes",
             ordered_json::array({vec(axes.col(0)), vec(axes.col(1)), vec(axes.col(2))})},
            {"triangles", model->mesh.triangles.size()},
            {"source_triangles", model->source_triangles},
            {"welded_vertices", model->welded_vertices},
            {"degenerate_triangles_dropped", model->degenerate_triangles},
            {"hull_vertices", model->hull_vertices.size()},
            {"hull_faces", model->hull_faces},
            {"repair",
             r.scene ? std::string(kMeshRepairNames[static_cast<int>(r.scene->bodies[i].repair)])
                     : std::string()},
            {"repair_note", model->repair_note}};
      }
      bodies.push_back(body);
    }
  j["bodies"] = bodies;
  write_file_atomically(path, j.dump(2) + "\n");
}

}  // namespace tumble
