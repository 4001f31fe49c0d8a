// The embedded default scene (played when sylva-player gets no scene file). It is assembled from
// the modules this program was built with, so a lean build still has a valid default: the
// meadow is terrain (or the built-in ground) + forest + grass where those modules exist.

#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene_document.hpp>

namespace sylva::scene {

std::string default_scene_text() {
  nlohmann::json j;
  j["sylva_scene"] = kSceneFormatVersion;
  j["name"] = "Default meadow";
  // Standing in the meadow, looking along it toward the hills.
  j["camera"] = {{"position", {4.0, 1.7, 26.0}}, {"height_mode", "above_ground"}, {"yaw_deg", 8.0},
                 {"pitch_deg", -4.0}, {"fov_deg", 60.0}};
  j["sun"] = {{"follow_clock", true}, {"intensity", 1.8}, {"fog_density", 0.0012}};
  j["environment"] = {{"time_of_day_h", 10.0}, {"season", 0.2}, {"latitude_deg", 47.0}};
  j["wind"] = {{"direction_deg", 30.0}, {"strength", 4.0}, {"gust_amplitude", 3.0}};
  const nlohmann::json source = {{"size", 1600.0},
                                 {"resolution", 257},
                                 {"height", 60.0},
                                 {"generator", "hills_and_ridges"},
                                 {"noise", {{"octaves", 6}, {"frequency", 0.0016}, {"seed", 11}}}};
  if (find_module("terrain")) {
    j["terrain"] = source;
    // A green meadow: no snow or sand, and the terrain's grass tone close to the built-in ground's
    // (the terrain's default grass is authored for tone mapping and is too bright without it).
    j["terrain"]["render"] = {{"material", {{"snow_height", 1.0}, {"sand_height", 0.0}, {"grass_color", {0.2, 0.31, 0.11}}}}};
  } else {
    j["ground"] = source;
    j["ground"]["snow_fraction"] = 1.0;  // no snow on meadow hills
  }
  if (find_module("grass")) {
    j["grass"] = {{"area_min", {-30.0, -40.0}}, {"area_max", {30.0, 40.0}}, {"field", {{"density", 100.0}}}};
  }
  if (find_module("vegetation")) {
    // Broadleaf trees scattered over the meadow and up the slope ahead.
    j["vegetation"] = {{"area_min", {-70.0, -110.0}}, {"area_max", {70.0, -2.0}}, {"trees_per_hectare", 22.0},
                       {"min_spacing", 7.0}, {"species", "broadleaf"}};
  }
  j["bookmarks"] = {{"overview", {{"position", {-160.0, 90.0, 160.0}}, {"yaw_deg", -45.0}, {"pitch_deg", -20.0}}}};
  j["camera_paths"] = {
      {"walk",
       {{"interpolation", "catmull_rom"},
        {"keys",
         {{{"time_s", 0.0}, {"position", {4.0, 1.7, 26.0}}, {"height_mode", "above_ground"}, {"yaw_deg", 8.0}, {"pitch_deg", -4.0}},
          {{"time_s", 6.0}, {"position", {0.0, 2.5, 0.0}}, {"height_mode", "above_ground"}, {"yaw_deg", 30.0}, {"pitch_deg", -8.0}},
          {{"time_s", 12.0}, {"position", {-10.0, 6.0, -30.0}}, {"height_mode", "above_ground"}, {"yaw_deg", 90.0}, {"pitch_deg", -12.0}}}}}}};
  return j.dump(2) + "\n";
}

Result<SceneDocument> default_scene(std::vector<std::string>& warnings) {
  return SceneDocument::from_text(default_scene_text(), "<embedded default scene>", warnings);
}

}  // namespace sylva::scene
