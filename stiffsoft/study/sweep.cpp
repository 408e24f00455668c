#include <stiffsoft/study/sweep.hpp>

#include <cstdint>
#include <cstdio>
#include <filesystem>

#include <stiffsoft/scene/scene_loader.hpp>

namespace stiffsoft::study {

namespace {

using nlohmann::json;

/// An override to apply: scene pointer, value, and where the study states it.
struct Override {
  std::string pointer;   ///< JSON pointer into the scene
  json value;            ///< new value
  std::string origin;    ///< JSON path in the study file
};

json resolved_base(const StudySpec& study) {
  try {
    return resolved_scene_json(load_scene(study.scene));
  } catch (const std::exception& e) {
    throw StudyError(study.file.string() + ": /scene: the base scene does not load: " + e.what());
  }
}

/// The base scene with `overrides` applied, validated and resolved again.
json scene_with(const StudySpec& study, const json& base, const std::vector<Override>& overrides) {
  json scene = base;
  for (const Override& o : overrides) {
    json::json_pointer pointer;
    try {
      pointer = json::json_pointer(o.pointer);
    } catch (const json::exception& e) {
      throw StudyError(study.file.string() + ": " + o.origin + ": '" + o.pointer + "' is not a JSON pointer: " + e.what());
    }
    if (!scene.contains(pointer)) {
      const json::json_pointer parent = pointer.parent_pointer();
      if (!scene.contains(parent) || !scene.at(parent).is_object())
        throw StudyError(study.file.string() + ": " + o.origin + ": '" + o.pointer + "' is not a key of the scene " +
                         study.scene.string());
    }
    const json& old = scene.contains(pointer) ? scene.at(pointer) : json();
    if (!old.is_null() && (old.is_number() != o.value.is_number() || old.is_string() != o.value.is_string() ||
                           old.is_boolean() != o.value.is_boolean() || old.is_array() != o.value.is_array() ||
                           old.is_object() != o.value.is_object()))
      throw StudyError(study.file.string() + ": " + o.origin + ": " + o.pointer + " = " + o.value.dump() +
                       " has the wrong type: the scene has " + old.dump() + " there");
    scene[pointer] = o.value;
  }
  try {
    const SceneDescription description = load_scene_from_string(
        scene.dump(), study.scene.parent_path(), study.scene.string() + " (as changed by the study)", "run");
    return resolved_scene_json(description);
  } catch (const std::exception& e) {
    std::string where;
    for (const Override& o : overrides) where += (where.empty() ? "" : ", ") + o.origin;
    throw StudyError(study.file.string() + ": " + where + ": the changed scene is not valid: " + e.what());
  }
}

std::vector<Override> fixed_overrides(const StudySpec& study) {
  std::vector<Override> out;
  for (const auto& [key, value] : study.set.items()) out.push_back({key, value, "/set/" + key});
  return out;
}

RunPlan plan_for(const StudySpec& study, const json& base, std::map<std::string, json> parameters,
                 std::vector<Override> overrides) {
  RunPlan run;
  run.scene = scene_with(study, base, overrides);
  json physics = run.scene;  // the description does not change results: editing it keeps the cache
  physics.erase("description");
  run.hash = fnv1a_hex(physics.dump());
  run.x = parameters.at(study.sweep[study.x].path).get<double>();
  run.series = series_label(study, parameters);
  run.parameters = std::move(parameters);
  return run;
}

/// A swept value as text: strings without quotes (file paths: their stem), numbers in %g form (1e+07, 0.001).
std::string value_text(const json& v) {
  if (v.is_string()) {  // a file path: its stem
    const std::string text = v.get<std::string>();
    return text.find('/') == std::string::npos ? text : std::filesystem::path(text).stem().string();
  }
  if (v.is_number_float()) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", v.get<double>());
    return buffer;
  }
  return v.dump();
}

}  // namespace

std::string fnv1a_hex(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buffer[17];
  std::snprintf(buffer, sizeof(buffer), "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

std::string series_label(const StudySpec& study, const std::map<std::string, json>& parameters) {
  std::string label;
  for (int i = 0; i < int(study.sweep.size()); ++i) {
    if (i == study.x) continue;
    const json& v = parameters.at(study.sweep[i].path);
    label += (label.empty() ? "" : ", ") + (study.sweep[i].name.empty() ? "" : study.sweep[i].name + "=") +
             value_text(v);
  }
  return label;
}

Plan make_plan(const StudySpec& study) {
  const json base = resolved_base(study);
  Plan plan;
  // Cartesian product, the last parameter varying fastest; the x parameter is listed first
  // within each series because series are grouped by label afterwards.
  std::vector<std::size_t> index(study.sweep.size(), 0);
  for (;;) {
    std::map<std::string, json> parameters;
    std::vector<Override> overrides = fixed_overrides(study);
    for (std::size_t i = 0; i < study.sweep.size(); ++i) {
      const SweepParameter& p = study.sweep[i];
      parameters[p.path] = p.values[index[i]];
      overrides.push_back({p.path, p.values[index[i]], "/sweep/" + std::to_string(i) + "/values/" + std::to_string(index[i])});
    }
    plan.runs.push_back(plan_for(study, base, parameters, overrides));
    bool advanced = false;  // odometer step: the last parameter fastest
    for (std::size_t k = study.sweep.size(); k-- > 0 && !advanced;) {
      if (++index[k] < study.sweep[k].values.size()) advanced = true;
      else index[k] = 0;
    }
    if (!advanced) break;
  }
  for (const RunPlan& r : plan.runs)
    if (std::find(plan.series.begin(), plan.series.end(), r.series) == plan.series.end()) plan.series.push_back(r.series);
  // Extra reference runs: the series' scene (x at its first value) with the quantity's overrides.
  for (std::size_t q = 0; q < study.quantities.size(); ++q) {
    const ReferenceSpec& ref = study.quantities[q].reference;
    if (ref.kind != ReferenceKind::Run) continue;
    for (const std::string& series : plan.series) {
      const auto first = std::find_if(plan.runs.begin(), plan.runs.end(), [&](const RunPlan& r) { return r.series == series; });
      std::vector<Override> overrides = fixed_overrides(study);
      for (std::size_t i = 0; i < study.sweep.size(); ++i)
        overrides.push_back({study.sweep[i].path, first->parameters.at(study.sweep[i].path), "/sweep/" + std::to_string(i)});
      for (const auto& [key, value] : ref.overrides.items())
        overrides.push_back({key, value, study.quantities[q].json_path + "/reference/run/" + key});
      RunPlan run = plan_for(study, base, first->parameters, overrides);
      if (ref.overrides.contains(study.sweep[study.x].path) && ref.overrides.at(study.sweep[study.x].path).is_number())
        run.x = ref.overrides.at(study.sweep[study.x].path).get<double>();
      plan.reference_runs[std::to_string(q) + "|" + series] = std::move(run);
    }
  }
  return plan;
}

}  // namespace stiffsoft::study
