/// @file Islands of DOF blocks (BlockIslands) and the line search that gives each island its own
/// CCD bound: the islands' union–find, that the energy of a run's iterates is a sum over the
/// islands the terms declare (so a missed coupling fails here), and what it buys boxes that land
/// at the same time far apart.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <stiffsoft/coupling/model/block_islands.hpp>

#include "scene_helpers.hpp"

using namespace stiffsoft;

namespace {

/// Two stacks 0.8 m apart over a fixed floor: in each, a 0.1 m box turned onto an edge or a
/// corner falls onto a box resting on the floor; with friction.
const char* kTwoStacks = R"({"description": "two stacks",
  "time": {"dt": 0.004166667},
  "contact": {"dhat": 0.001, "mu": 0.3},
  "bodies": [
    {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [2, 0.1, 2]}, "position": [0, -0.05, 0]},
    {"name": "low0", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [-0.4, 0.052, 0]},
    {"name": "high0", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [-0.4, 0.2, 0],
     "rotation_deg": [20, 35, 10], "velocity": [0.2, -1, 0]},
    {"name": "low1", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0.4, 0.052, 0]},
    {"name": "high1", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0.4, 0.2, 0.01],
     "rotation_deg": [40, 0, 15], "velocity": [0, -1.2, 0.1]}]})";

/// A soft block resting on a fixed floor with a box falling onto it, and a box falling onto the
/// floor 0.6 m away; with friction.
const char* kSoftAndAffine = R"({"description": "a soft block and boxes",
  "time": {"dt": 0.004166667},
  "contact": {"dhat": 0.001, "mu": 0.3},
  "bodies": [
    {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [2, 0.1, 2]}, "position": [0, -0.05, 0]},
    {"name": "block", "model": "soft", "mesh": {"primitive": "box", "size": [0.2, 0.1, 0.2]}, "position": [-0.3, 0.052, 0],
     "mesh_size": 0.05, "density": 500, "material": {"model": "stable_neo_hookean", "young": 100000, "poisson": 0.3}},
    {"name": "on_block", "mesh": {"primitive": "box", "size": [0.08, 0.08, 0.08]}, "position": [-0.3, 0.2, 0],
     "rotation_deg": [20, 35, 10], "velocity": [0.1, -1, 0]},
    {"name": "on_floor", "mesh": {"primitive": "box", "size": [0.08, 0.08, 0.08]}, "position": [0.3, 0.1, 0],
     "rotation_deg": [40, 0, 15], "velocity": [0, -1, 0]}]})";

/// A box dropped fast onto a fixed floor, and a second box in free flight 1 m above it. Without
/// the springs on entering pairs, which would spare the impact its cut directions.
std::string impact_and_flight(bool islands) {
  return std::string(R"({"description": "an impact and a free flight",
    "time": {"dt": 0.004166667},
    "contact": {"dhat": 0.001, "mu": 0.3},
    "solver": {"island_line_search": )") + (islands ? "true" : "false") + R"(, "entering_springs": false},
    "bodies": [
      {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [2, 0.1, 2]}, "position": [0, -0.05, 0]},
      {"name": "falling", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, 0.1, 0],
       "rotation_deg": [20, 35, 10], "velocity": [0, -3, 0]},
      {"name": "flying", "mesh": {"primitive": "box", "size": [0.1, 0.1, 0.1]}, "position": [0.3, 1.0, 0],
       "velocity": [0.5, 0, 0]}]})";
}

}  // namespace

TEST(BlockIslands, JoinsNumbersAndScalesByIsland) {
  BlockIslands islands(5);
  islands.join(0, 3);
  islands.join(3, 4);
  islands.join(2, -1);  // a vertex without DOFs couples nothing
  islands.number();
  ASSERT_EQ(islands.count(), 3);
  EXPECT_EQ(islands.island(0), 0);
  EXPECT_EQ(islands.island(3), 0);
  EXPECT_EQ(islands.island(4), 0);
  EXPECT_EQ(islands.island(1), 1);
  EXPECT_EQ(islands.island(2), 2);

  BlockIslands one(5);
  one.join(1, 2);
  one.join_all();
  one.number();
  EXPECT_EQ(one.count(), 1);
  for (int b = 0; b < 5; ++b) EXPECT_EQ(one.island(b), 0);

  BlockIslands none(0);  // no DOF blocks: still one island, so that Newton has a bound
  none.number();
  EXPECT_EQ(none.count(), 1);
}

TEST(BlockIslands, ScalesEachBlockByItsIslandAndIgnoresFixedVertices) {
  Simulation sim = stiffsoft::testing::simulate(kTwoStacks);
  const Model& model = sim.model();
  BlockIslands islands(int(model.blocks.size()));
  // A floor vertex (no DOFs) with a vertex of box0: nothing joined. Then box1 with box3.
  const auto first_vertex = [&](int body) {
    for (std::size_t v = 0; v < model.mesh.vertex_body.size(); ++v)
      if (model.mesh.vertex_body[v] == body) return int(v);
    return -1;
  };
  const std::vector<int> block = vertex_blocks(model);
  islands.join_blocks({block[first_vertex(0)], block[first_vertex(1)], -1, -1});
  islands.join_blocks({block[first_vertex(2)], block[first_vertex(4)], -1, -1});
  islands.number();
  EXPECT_EQ(islands.count(), 3);
  EXPECT_EQ(vertex_block(model, first_vertex(0)), -1);
  const Eigen::VectorXd dq = Eigen::VectorXd::Ones(model.num_dofs);
  std::vector<double> scale(std::size_t(islands.count()));
  for (int i = 0; i < islands.count(); ++i) scale[std::size_t(i)] = 0.25 * (i + 1);
  const Eigen::VectorXd scaled = islands.scaled(model, dq, scale);
  for (int b = 1; b <= 4; ++b) {
    const BodyModel& body = model.bodies[std::size_t(b)];
    const double s = scale[std::size_t(islands.island(body.block))];
    EXPECT_EQ(scaled.segment<12>(body.dof), Eigen::VectorXd::Constant(12, s)) << "body " << b;
  }
  EXPECT_EQ(islands.island(model.bodies[2].block), islands.island(model.bodies[4].block));
  EXPECT_NE(islands.island(model.bodies[1].block), islands.island(model.bodies[2].block));
}

namespace {

/// Worst relative defect, over the directions of `steps` steps of `scene` with at least two
/// islands, of the energy change of moving two disjoint sets of islands (each island half-way
/// to its CCD bound) against the sum of the two sets' changes alone; counts the directions
/// checked and the steps with contacts.
double worst_defect_of_the_sum_over_islands(const std::string& scene, int steps, int& checked, int& contact_steps) {
  Simulation sim = stiffsoft::testing::simulate(scene);
  checked = contact_steps = 0;
  double worst = 0;
  sim.observe_newton([&](const NewtonIterate& it) {
    const Eigen::MatrixX3d dx = it.model.surface_step(it.p);
    BlockIslands islands(int(it.model.blocks.size()));
    for (const EnergyTerm* t : it.terms) t->join_coupled_blocks(it.c, dx, islands);
    islands.number();
    if (islands.count() < 2) return;
    std::vector<double> bound(std::size_t(islands.count()), 1.0);
    for (const EnergyTerm* t : it.terms) t->max_step_per_island(it.c, it.p, dx, islands, bound);
    std::vector<double> even(bound.size(), 0.0), odd(bound.size(), 0.0);
    for (std::size_t i = 0; i < bound.size(); ++i) (i % 2 ? odd : even)[i] = 0.5 * bound[i];
    const auto energy = [&](const Eigen::VectorXd& q) {
      const Eigen::MatrixX3d x = it.model.surface(q);
      for (EnergyTerm* t : it.terms) t->update({q, x});
      double e = 0;
      for (const EnergyTerm* t : it.terms) e += t->value({q, x});
      return e;
    };
    const Eigen::VectorXd a = islands.scaled(it.model, it.p, even), b = islands.scaled(it.model, it.p, odd);
    const double e0 = energy(it.c.q), ea = energy(it.c.q + a), eb = energy(it.c.q + b), eab = energy(it.c.q + a + b);
    for (EnergyTerm* t : it.terms) t->update(it.c);
    const double change = std::abs(ea - e0) + std::abs(eb - e0);
    if (change == 0) return;
    worst = std::max(worst, std::abs((eab - e0) - (ea - e0) - (eb - e0)) / change);
    ++checked;
  });
  for (int k = 0; k < steps; ++k) contact_steps += sim.step().contacts > 0;
  return worst;
}

}  // namespace

// At every direction of a run with contacts and friction, moving two disjoint sets of the
// islands the terms declare changes the energy by the sum of what each set's move changes it
// by: the terms couple no blocks they did not join. A coupling a term failed to declare (a
// contact candidate, a friction stencil, a soft element) breaks the sum by that stencil's
// energy: without the barrier's joins the defect here is 0.18.
TEST(IslandLineSearch, TheEnergyIsASumOverTheIslandsTheTermsDeclare) {
  int checked = 0, contact_steps = 0;
  const double worst = worst_defect_of_the_sum_over_islands(kTwoStacks, 40, checked, contact_steps);
  std::printf("two stacks: %d directions checked, %d steps with contacts, worst relative defect %.2e\n", checked,
              contact_steps, worst);
  EXPECT_GE(contact_steps, 20);
  EXPECT_GE(checked, 40);
  EXPECT_LT(worst, 1e-9);
}

// The same with a soft block (elasticity couples its nodes) that a box lands on, beside a box
// landing on the floor.
TEST(IslandLineSearch, TheEnergyIsASumOverTheIslandsWithASoftBody) {
  int checked = 0, contact_steps = 0;
  const double worst = worst_defect_of_the_sum_over_islands(kSoftAndAffine, 30, checked, contact_steps);
  std::printf("soft block and boxes: %d directions checked, %d steps with contacts, worst relative defect %.2e\n",
              checked, contact_steps, worst);
  EXPECT_GE(contact_steps, 15);
  EXPECT_GE(checked, 20);
  EXPECT_LT(worst, 1e-9);
}

// A box in free flight far from an impact: its energy (inertia, gravity, the orthogonality at a
// rotation) is quadratic along its direction, so Newton's first step lands it where the step
// ends. With one CCD bound for all, the impact below cuts that step short and the next
// directions still move the flying box; with a bound per island they do not.
TEST(IslandLineSearch, AnImpactNoLongerHoldsBackABodyInFreeFlight) {
  const auto run = [](bool islands, int& iterations, int& flying_moved) {
    Simulation sim = stiffsoft::testing::simulate(impact_and_flight(islands));
    const int dof = sim.model().bodies[2].dof;
    iterations = flying_moved = 0;
    sim.observe_newton([&](const NewtonIterate& it) {
      if (it.iteration > 0 && it.p.segment<12>(dof).lpNorm<Eigen::Infinity>() > 1e-9) ++flying_moved;
    });
    int ccd_limited = 0;
    for (int k = 0; k < 24; ++k) {
      const StepStats s = sim.step();
      EXPECT_TRUE(s.newton.converged) << "step " << k + 1;
      EXPECT_GT(s.smallest_distance, 0);
      iterations += s.newton.iterations;
      ccd_limited += s.newton.ccd_limited_iterations;
    }
    EXPECT_GT(ccd_limited, 0);  // the impact cut some steps
    return Eigen::VectorXd(sim.q().segment<12>(dof));
  };
  int it_islands = 0, it_one = 0, moved_islands = 0, moved_one = 0;
  const Eigen::VectorXd flying_islands = run(true, it_islands, moved_islands);
  const Eigen::VectorXd flying_one = run(false, it_one, moved_one);
  std::printf("Newton iterations over 24 steps: %d with a bound per island, %d with one; later directions that "
              "moved the flying box: %d and %d\n",
              it_islands, it_one, moved_islands, moved_one);
  EXPECT_EQ(moved_islands, 0);
  EXPECT_GT(moved_one, 0);
  EXPECT_LE(it_islands, it_one);
  EXPECT_LT((flying_islands - flying_one).lpNorm<Eigen::Infinity>(), 1e-9);  // the same free flight
}
