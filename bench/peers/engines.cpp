#include "peers/engines.hpp"

#include <stdexcept>

#include "peers/stiffsoft_engine.hpp"
#ifdef STIFFSOFT_WITH_BULLET
#include "peers/bullet_engine.hpp"
#endif
#ifdef STIFFSOFT_WITH_MUJOCO
#include "peers/mujoco_engine.hpp"
#endif

namespace stiffsoft::peers {

std::vector<std::string> available_engines() {
  std::vector<std::string> names{"stiffsoft", "stiffsoft-coarse", "stiffsoft-sleep"};
#ifdef STIFFSOFT_WITH_BULLET
  names.push_back("bullet_mesh");
  names.push_back("bullet_mesh-awake");
  names.push_back("bullet");
#endif
#ifdef STIFFSOFT_WITH_MUJOCO
  names.push_back("mujoco");
  names.push_back("mujoco-cg");
#endif
  return names;
}

std::string available_engine_list() {
  std::string list;
  for (const std::string& name : available_engines()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

std::unique_ptr<Engine> make_engine(const std::string& name, const PeerScene& scene, const EngineOptions& options) {
  if (name == "stiffsoft") return std::make_unique<StiffsoftEngine>(scene, scene.settings, name);
  if (name == "stiffsoft-coarse") return std::make_unique<StiffsoftEngine>(scene, coarse_settings(scene), name);
  if (name == "stiffsoft-sleep") {
    SimulationSettings settings = scene.settings;
    settings.sleep_time = options.sleep_time;
    return std::make_unique<StiffsoftEngine>(scene, settings, name);
  }
#ifdef STIFFSOFT_WITH_BULLET
  if (name == "bullet" || name == "bullet_mesh" || name == "bullet_mesh-awake") {
    BulletSettings settings;
    settings.margin = options.bullet_margin > 0 ? options.bullet_margin : 0.5 * scene.dhat;
    settings.shapes = name == "bullet" ? BulletShapes::hulls : BulletShapes::meshes;
    settings.sleeping = name != "bullet_mesh-awake";
    return std::make_unique<BulletEngine>(scene, settings);
  }
#endif
#ifdef STIFFSOFT_WITH_MUJOCO
  if (name == "mujoco" || name == "mujoco-cg") {
    int geoms = 0;
    for (const PeerBody& body : scene.bodies)
      if (!body.fixed) geoms += body.torus ? body.torus->n : 1;
    MjcfSizes sizes;
    sizes.nconmax = options.mujoco_nconmax > 0 ? options.mujoco_nconmax : 4 * geoms + 200;
    sizes.njmax = options.mujoco_njmax > 0 ? options.mujoco_njmax : 4 * sizes.nconmax;
    return std::make_unique<MujocoEngine>(scene, sizes, name, name == "mujoco-cg" ? "CG" : "");
  }
#endif
  throw std::invalid_argument("engine '" + name + "' is not available in this build (available: " +
                              available_engine_list() + ")");
}

}  // namespace stiffsoft::peers
