// The embedded default scene (played when sylva-player gets no scene file): a composed vista,
// meadow in front, mixed forest in the middle distance, mountains behind, evening sun. It is
// assembled from the modules this program was built with, so a lean build still has a valid
// default: the valley is terrain (or the built-in ground) + forest + grass where those exist.

#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene_document.hpp>

namespace sylva::scene {

std::string default_scene_text() {
  nlohmann::json j;
  j["sylva_scene"] = kSceneFormatVersion;
  j["name"] = "Default vista: meadow, mixed forest, mountains";
  // Standing in the meadow in the evening, looking north across it to a mixed forest and the
  // mountains behind; the sun low in the west lights the peaks warm and throws the forest's
  // shadows long across the grass (issue #19).
  j["camera"] = {{"position", {10.0, 2.2, 50.0}}, {"height_mode", "above_ground"}, {"yaw_deg", -15.0},
                 {"pitch_deg", -1.0}, {"fov_deg", 60.0}};
  j["sun"] = {{"follow_clock", true}};
  j["environment"] = {{"time_of_day_h", 18.0}, {"season", 0.2}, {"latitude_deg", 47.0}};
  j["wind"] = {{"direction_deg", 30.0}, {"strength", 4.0}, {"gust_amplitude", 3.0}};
  // A valley: rolling meadow around the origin, mountains from about 500 m out (height_source.hpp).
  const nlohmann::json source = {{"size", 8000.0},
                                 {"resolution", 513},
                                 {"height", 1300.0},
                                 {"generator", "valley"},
                                 {"noise", {{"octaves", 7}, {"frequency", 0.0006}, {"seed", 11}}}};
  if (find_module("terrain")) {
    j["terrain"] = source;
    // An alpine valley: the meadow at about 1200 m, peaks reaching the rock and snow lines.
    j["terrain"]["render"] = {{"material", {{"base_altitude_m", 1200.0}}}};
  } else {
    j["ground"] = source;
  }
  if (find_module("grass")) {
    // Blades near the camera; clumps and the grass's ground layer carry the meadow's colour on to
    // the forest and the mountain feet (rock stays bare: far.max_slope_deg).
    j["grass"] = {{"area_min", {-60.0, -60.0}},
                  {"area_max", {60.0, 60.0}},
                  {"field", {{"density", 100.0}}},
                  {"blade", {{"width_min", 0.014}, {"width_max", 0.03}}},
                  {"far", {{"clump_margin", 150.0}, {"ground_margin", 800.0}, {"ground_spacing", 6.25}, {"texture_scale", 1.5}}}};
  }
  if (find_module("vegetation")) {
    // A mixed stand with clearings across the middle distance, beyond the meadow.
    j["vegetation"] = {{"area_min", {-420.0, -520.0}}, {"area_max", {420.0, -25.0}}, {"trees_per_hectare", 45.0},
                       {"min_spacing", 6.0}, {"clearings", 0.35}, {"clearing_size", 160.0},
                       {"mix", {{"broadleaf", 3.0}, {"conifer", 2.0}, {"birch", 1.5}}}};
  }
  j["bookmarks"] = {{"overview", {{"position", {-260.0, 140.0, 260.0}}, {"yaw_deg", -40.0}, {"pitch_deg", -14.0}}}};
  j["camera_paths"] = {
      {"walk",
       {{"interpolation", "catmull_rom"},
        {"keys",
         {{{"time_s", 0.0}, {"position", {10.0, 2.2, 50.0}}, {"height_mode", "above_ground"}, {"yaw_deg", -15.0}, {"pitch_deg", -1.0}},
          {{"time_s", 6.0}, {"position", {0.0, 2.5, 0.0}}, {"height_mode", "above_ground"}, {"yaw_deg", 20.0}, {"pitch_deg", -4.0}},
          {{"time_s", 12.0}, {"position", {-10.0, 6.0, -50.0}}, {"height_mode", "above_ground"}, {"yaw_deg", 60.0}, {"pitch_deg", -6.0}}}}}}};
  return j.dump(2) + "\n";
}

Result<SceneDocument> default_scene(std::vector<std::string>& warnings) {
  return SceneDocument::from_text(default_scene_text(), "<embedded default scene>", warnings);
}

}  // namespace sylva::scene
