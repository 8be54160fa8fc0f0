// `pcrf frame`: what a frame is before any ground motion (frame_properties.hpp), as aligned
// text or one JSON object.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/frame_flags.hpp"
#include "cli/setting_flags.hpp"
#include "pcrf/api/frame_input.hpp"
#include "pcrf/json.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame_properties.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf::cli {
namespace {

struct FrameOptions {
  SceneFlags scene;
  std::unique_ptr<SettingFlags<PhysicsOptions>> physics;
  double points = api::kDefaultPushoverPoints;  ///< checked by api::pushover_points
  bool json = false;
  double period_s = 0.0;  ///< > 0: also FEMA P-695's period-based ductility at this period
};

/// Rotations at which the curve is sampled for the ductility (finer than any printed curve,
/// and independent of --points).
constexpr int kDuctilityPoints = 2001;

void add_ductility(JsonObject& json, double period_s, const P695Ductility& d) {
  json.number("p695_period_s", period_s)
      .number("p695_ultimate_rotation_rad", d.ultimate_rotation_rad)
      .number("p695_ultimate_displacement_m", d.ultimate_displacement_m)
      .number("p695_yield_displacement_m", d.yield_displacement_capacity_m)
      .number("p695_mu_t", d.mu_t_capacity)
      .number("p695_yield_displacement_uplift_m", d.yield_displacement_uplift_m)
      .number("p695_mu_t_uplift", d.mu_t_uplift);
}

void print_ductility(double period_s, const P695Ductility& d) {
  std::printf("\nFEMA P-695 period-based ductility at T = %g s (docs/p695_rocking_frame.md)\n", period_s);
  std::printf("%-38s %12.6g rad\n", "capacity lost at rotation", d.ultimate_rotation_rad);
  std::printf("%-38s %12.6g m\n", "roof displacement there delta_u", d.ultimate_displacement_m);
  std::printf("%-38s %12.6g m\n", "delta_y,eff (V_max = pushover peak)", d.yield_displacement_capacity_m);
  std::printf("%-38s %12.6g  (the engine's convention)\n", "mu_T = delta_u / delta_y,eff", d.mu_t_capacity);
  std::printf("%-38s %12.6g m\n", "delta_y,eff (V_max = uplift threshold)", d.yield_displacement_uplift_m);
  std::printf("%-38s %12.6g\n", "mu_T with yield at uplift", d.mu_t_uplift);
}

JsonObject as_json(const FrameProperties& p) {
  std::vector<double> theta, accel;
  for (const auto& point : p.pushover) theta.push_back(point.theta_rad), accel.push_back(point.accel_g);
  JsonObject json;
  for (const auto& info : frame_property_table()) json.number(info.key, p.*info.member);
  json.text("fracture_tendon", p.fracture_tendon).numbers("pushover_theta_rad", theta).numbers("pushover_accel_g", accel);
  return json;
}

void print_text(const FrameProperties& p) {
  for (const auto& info : frame_property_table()) {
    std::string unit(info.units == "1" ? "" : info.units);
    if (info.member == &FrameProperties::fracture_angle_rad)
      unit += p.fracture_tendon.empty() ? " (no tendon fractures)" : " (" + p.fracture_tendon + " tendon)";
    std::printf("%-38s %12.6g %s\n", std::string(info.label).c_str(), p.*info.member, unit.c_str());
  }
  std::printf("\nstatic pushover: ground acceleration that holds the frame at theta1\n%14s %14s\n", "theta1 [rad]",
              "accel [g]");
  for (const auto& point : p.pushover) std::printf("%14.6g %14.6g\n", point.theta_rad, point.accel_g);
}

void describe(const FrameOptions& o) {
  const int points = api::pushover_points(o.points);
  const PhysicsOptions physics = o.physics->resolve();
  ScenePoint point;
  const auto scene = o.scene.scene(&point);
  const FrameProperties p = frame_properties(*scene, physics.fracture_strain, points);
  std::optional<P695Ductility> ductility;
  if (o.period_s != 0.0) {
    if (!(o.period_s > 0.0)) throw UserError("period_s", "must be positive");
    // The roof displacement needs a height: a scene whose table has h_m.
    const SceneSpec spec{&scene_model(o.scene.model), point};
    if (std::isnan(spec.value("h_m")))
      throw UserError("period_s", "the P-695 ductility needs the frame's height {} (" + models_taking("h_m") + ")", {"h_m"});
    ductility = p695_ductility(frame_properties(*scene, physics.fracture_strain, kDuctilityPoints), spec.value("h_m"), o.period_s);
  }
  if (o.json) {
    JsonObject json = as_json(p);
    if (ductility) add_ductility(json, o.period_s, *ductility);
    std::cout << json.str() << std::endl;
  } else {
    print_text(p);
    if (ductility) print_ductility(o.period_s, *ductility);
  }
}

}  // namespace

void add_frame_command(CLI::App& app) {
  auto o = std::make_shared<FrameOptions>();
  CLI::App* cmd = app.add_subcommand(
      "frame", "A scene's properties (threshold, r, p, stop angles) and its static pushover curve");
  o->scene.add_to(cmd);
  o->physics = std::make_unique<SettingFlags<PhysicsOptions>>(cmd, physics_settings());
  cmd->add_option("--points", o->points,
                  "rotations at which the pushover curve is printed (2 to " + std::to_string(api::kMaxPushoverPoints) + ")")->capture_default_str();
  cmd->add_flag("--json", o->json, "one JSON object instead of text");
  cmd->add_option("--period-s", o->period_s,
                  "also FEMA P-695's period-based ductility mu_T at this archetype period T [s] (PCRF only)");
  cmd->callback([o] { describe(*o); });
}

}  // namespace pcrf::cli
