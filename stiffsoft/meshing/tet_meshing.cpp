#include <stiffsoft/meshing/tet_meshing.hpp>

#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <stiffsoft/meshing/gmsh_model.hpp>
#include <stiffsoft/meshing/gmsh_session.hpp>
#include <stiffsoft/meshing/mesh_checks.hpp>
#include <stiffsoft/meshing/read_surface_mesh.hpp>
#include <stiffsoft/meshing/tet_msh_io.hpp>
#include <stiffsoft/meshing/tet_surface_solids.hpp>

namespace stiffsoft {
namespace {

void require_positive(double value, const std::string& what) {
  // `!(value > 0)` also rejects NaN.
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::invalid_argument(what + " must be a positive finite number, got " + std::to_string(value));
}

void check_options(const TetMeshOptions& options, const std::string& what) {
  require_positive(options.h, what + ": mesh size h");
  if (options.elements_per_circle < 0)
    throw std::invalid_argument(what + ": elements_per_circle must be >= 0, got " +
                                std::to_string(options.elements_per_circle));
  if (!(options.feature_angle_deg > 0.0 && options.feature_angle_deg <= 180.0))
    throw std::invalid_argument(what + ": feature_angle_deg must be in (0, 180], got " +
                                std::to_string(options.feature_angle_deg));
}

/// The mesh-size options every meshing session sets before it builds or loads geometry. Sizes at
/// geometry points are off: with them on, a point without an explicit size gets a default derived
/// from the model's bounding box, which overrides a larger h (seen: a 1 m box stayed at 0.24 m
/// edges for h = 0.4).
void set_mesh_size(const TetMeshOptions& options) {
  gmsh::option::setNumber("Mesh.MeshSizeMax", options.h);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", options.elements_per_circle);
}

/// Generates the 3D mesh and converts it; gmsh logs some failures (a surface it could not mesh)
/// as errors without throwing, and a partial mesh must not pass as a body.
TetMesh generate(const std::string& what) {
  gmsh::model::mesh::generate(3);
  if (const std::string errors = gmsh_logged_errors(); !errors.empty())
    throw std::runtime_error(what + ": gmsh: " + errors);
  return tet_mesh_from_gmsh_model(what);
}

std::string lowercase_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void require_readable(const std::filesystem::path& file) {
  // gmsh::open of a missing file logs nothing and throws nothing: check first.
  if (!std::ifstream(file, std::ios::binary)) throw std::runtime_error(file.string() + ": cannot open file");
}

/// OpenCASCADE prints its STEP parse errors to stdout whatever gmsh's settings: reject a file that is
/// not STEP at all before it gets there.
void require_step_header(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string word;
  in >> word;
  if (word.rfind("ISO-10303-21;", 0) != 0)
    throw std::runtime_error(file.string() + ": not a STEP file (expected 'ISO-10303-21;' first)");
}

/// Throws TetCountLimitError when the loaded solids, meshed at options.h, are expected to give more
/// than options.max_tets tetrahedra (see TetMeshOptions::max_tets). A .geo model may use gmsh's
/// built-in kernel, which OpenCASCADE's getMass would not know (and would log as an error that
/// fails the session), so it is bounded by its boxes.
void check_expected_tets(const gmsh::vectorpair& volumes, const TetMeshOptions& options, bool geo,
                         const std::string& what) {
  double volume = 0;
  for (const auto& [dim, tag] : volumes) {
    double v = 0;
    if (geo) {
      double x0, y0, z0, x1, y1, z1;
      gmsh::model::getBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1);
      v = (x1 - x0) * (y1 - y0) * (z1 - z0);
    } else {
      gmsh::model::occ::getMass(dim, tag, v);
    }
    volume += v;
  }
  const double expected = expected_tet_count(volume, options.h);
  if (expected > options.max_tets)
    throw TetCountLimitError(what + ": about " + std::to_string(expected) + " tetrahedra expected at h = " +
                                 std::to_string(options.h) + " m, more than " + std::to_string(options.max_tets),
                             volume, expected);
}

TetMesh mesh_cad_file(const std::filesystem::path& file, const TetMeshOptions& options, bool geo) {
  const std::string what = file.string();
  require_readable(file);
  TetMesh mesh;
  run_gmsh(what, options.verbose, [&] {
    set_mesh_size(options);
    gmsh::option::setString("Geometry.OCCTargetUnit", "M");
    if (geo) {
      gmsh::open(file.string());
      set_mesh_size(options);
      if (const std::string errors = gmsh_logged_errors(); !errors.empty())
        throw std::runtime_error(what + ": gmsh: " + errors);
      std::vector<int> types;
      gmsh::model::mesh::getElementTypes(types, 3);
      if (!types.empty()) {  // the script meshed itself
        mesh = tet_mesh_from_gmsh_model(what);
        return;
      }
    } else {
      gmsh::vectorpair imported;
      gmsh::model::occ::importShapes(file.string(), imported, /*highestDimOnly=*/true);
      gmsh::model::occ::synchronize();
      gmsh::vectorpair volumes;
      gmsh::model::getEntities(volumes, 3);
      if (volumes.size() > 1) {
        // Touching solids would otherwise get separate, non-matching meshes on their shared faces.
        gmsh::model::occ::removeAllDuplicates();
        gmsh::model::occ::synchronize();
      }
    }
    gmsh::vectorpair volumes;
    gmsh::model::getEntities(volumes, 3);
    if (volumes.empty()) throw std::runtime_error(what + ": defines no volume (solid) to mesh");
    if (options.max_tets > 0) check_expected_tets(volumes, options, geo, what);
    mesh = generate(what);
  });
  return mesh;
}

}  // namespace

double expected_tet_count(double volume, double h) { return volume / (h * h * h / (6.0 * std::sqrt(2.0))); }

TetMesh make_tet_mesh(const PrimitiveShape& shape, const TetMeshOptions& options) {
  using Type = PrimitiveShape::Type;
  const char* names[] = {"box", "sphere", "cylinder", "torus", "plane"};
  const std::string what = std::string("primitive ") + names[static_cast<int>(shape.type)];
  check_options(options, what);
  switch (shape.type) {
    case Type::Box:
    case Type::Plane:
      for (int d = 0; d < 3; ++d)
        require_positive(shape.extents[d], what + ": extents[" + std::to_string(d) + "]");
      break;
    case Type::Sphere:
    case Type::Cylinder:
      require_positive(shape.radius, what + ": radius");
      if (shape.type == Type::Cylinder) require_positive(shape.height, what + ": height");
      break;
    case Type::Torus:
      require_positive(shape.radius, what + ": radius (major)");
      require_positive(shape.minor_radius, what + ": minor_radius");
      if (!(shape.minor_radius < shape.radius))
        throw std::invalid_argument(what + ": minor_radius (" + std::to_string(shape.minor_radius) +
                                    ") must be smaller than radius (" + std::to_string(shape.radius) + ")");
      break;
  }
  TetMesh mesh;
  run_gmsh(what, options.verbose, [&] {
    set_mesh_size(options);
    namespace occ = gmsh::model::occ;
    switch (shape.type) {
      case Type::Box:
      case Type::Plane: {
        const Eigen::Vector3d e = shape.extents;
        occ::addBox(-0.5 * e.x(), -0.5 * e.y(), -0.5 * e.z(), e.x(), e.y(), e.z());
        break;
      }
      case Type::Sphere:
        occ::addSphere(0.0, 0.0, 0.0, shape.radius);
        break;
      case Type::Cylinder:
        occ::addCylinder(0.0, -0.5 * shape.height, 0.0, 0.0, shape.height, 0.0, shape.radius);
        break;
      case Type::Torus: {
        // OpenCASCADE's torus turns around z; a quarter turn about x puts its axis on y.
        const int torus = occ::addTorus(0.0, 0.0, 0.0, shape.radius, shape.minor_radius);
        occ::rotate({{3, torus}}, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -0.5 * std::numbers::pi);
        break;
      }
    }
    occ::synchronize();
    mesh = generate(what);
  });
  return mesh;
}

TetMesh make_tet_mesh(const SurfaceMesh& surface, const TetMeshOptions& options, const std::string& what) {
  check_options(options, what);
  check_closed_manifold(surface, what);
  check_not_self_intersecting(surface, what);
  const SurfaceSolids solids = surface_solids(surface, what);
  TetMesh mesh;
  run_gmsh(what, options.verbose, [&] {
    set_mesh_size(options);
    // One discrete surface per shell, so that outer boundaries and cavities make separate surface
    // loops. Only the vertices the faces use become nodes (check_closed_manifold allows unused ones).
    std::vector<std::size_t> tag_of_vertex(static_cast<std::size_t>(surface.V.rows()), 0);
    std::vector<int> shell_of_tag{-1};  // gmsh node tags start at 1
    std::vector<int> surfaces_of_shell;
    for (std::size_t k = 0; k < solids.shells.size(); ++k) {
      const int entity = gmsh::model::addDiscreteEntity(2);
      surfaces_of_shell.push_back(entity);
      std::vector<std::size_t> node_tags, face_tags, face_nodes;
      std::vector<double> coordinates;
      for (int f : solids.shells[k].faces) {
        face_tags.push_back(static_cast<std::size_t>(f) + 1);
        for (int c = 0; c < 3; ++c) {
          const auto v = static_cast<std::size_t>(surface.F(f, c));
          if (tag_of_vertex[v] == 0) {
            tag_of_vertex[v] = shell_of_tag.size();
            shell_of_tag.push_back(static_cast<int>(k));
            node_tags.push_back(tag_of_vertex[v]);
            for (int d = 0; d < 3; ++d) coordinates.push_back(surface.V(static_cast<Eigen::Index>(v), d));
          }
          face_nodes.push_back(tag_of_vertex[v]);
        }
      }
      gmsh::model::mesh::addNodes(2, entity, node_tags, coordinates);
      gmsh::model::mesh::addElementsByType(entity, 2, face_tags, face_nodes);  // type 2: 3-node triangle
    }

    std::vector<std::vector<int>> patches_of_shell(solids.shells.size());
    if (options.keep_surface) {
      for (std::size_t k = 0; k < solids.shells.size(); ++k) patches_of_shell[k] = {surfaces_of_shell[k]};
    } else {
      // Split at sharp edges into patches gmsh can parametrize, then remesh those with h. The
      // patches keep the input triangles and node tags until meshing: a node tells the shell.
      gmsh::model::mesh::classifySurfaces(options.feature_angle_deg * std::numbers::pi / 180.0,
                                          /*boundary=*/true,
                                          /*forReparametrization=*/true, /*curveAngle=*/std::numbers::pi);
      gmsh::model::mesh::createGeometry();
      gmsh::vectorpair patches;
      gmsh::model::getEntities(patches, 2);
      for (const auto& [dim, tag] : patches) {
        std::vector<std::size_t> triangles, nodes;
        gmsh::model::mesh::getElementsByType(2, triangles, nodes, tag);
        if (nodes.empty() || nodes.front() >= shell_of_tag.size())
          throw std::runtime_error(what + ": gmsh: surface patch " + std::to_string(tag) +
                                   " has no input triangles after classifySurfaces");
        patches_of_shell[static_cast<std::size_t>(shell_of_tag[nodes.front()])].push_back(tag);
      }
    }
    for (const SurfaceSolid& solid : solids.solids) {
      std::vector<int> loops{
          gmsh::model::geo::addSurfaceLoop(patches_of_shell[static_cast<std::size_t>(solid.outer)])};
      for (int cavity : solid.cavities)
        loops.push_back(gmsh::model::geo::addSurfaceLoop(patches_of_shell[static_cast<std::size_t>(cavity)]));
      gmsh::model::geo::addVolume(loops);
    }
    gmsh::model::geo::synchronize();
    mesh = generate(what);
  });
  return mesh;
}

TetMesh make_tet_mesh(const std::filesystem::path& file, const TetMeshOptions& options) {
  const std::string ext = lowercase_extension(file);
  if (ext == ".msh") return read_msh(file, options.verbose);
  check_options(options, file.string());
  if (ext == ".stl" || ext == ".obj") return make_tet_mesh(read_surface_mesh(file), options, file.string());
  if (ext == ".step" || ext == ".stp") {
    require_readable(file);
    require_step_header(file);
  }
  if (ext == ".step" || ext == ".stp" || ext == ".brep") return mesh_cad_file(file, options, false);
  if (ext == ".geo") return mesh_cad_file(file, options, true);
  throw std::invalid_argument(file.string() + ": unknown mesh file extension '" + ext +
                              "' (expected .stl, .obj, .step, .stp, .brep, .geo or .msh)");
}

TetMesh make_tet_mesh(const TetMeshRecipe& recipe) {
  if (recipe.primitive) return make_tet_mesh(*recipe.primitive, recipe.options);
  return make_tet_mesh(recipe.file, recipe.options);
}

}  // namespace stiffsoft
