#pragma once
/// @file Bodies at rest taken out of the steps, as rigid-body engines put them to sleep (Bullet's
/// deactivation), body by body: a dynamic affine body sleeps once it has moved no surface point
/// faster than a speed v_s for a time t_s while touching something, and so has every dynamic body
/// it touches (or that one sleeps). A sleeping body is held where it is, its velocity zero, until a
/// body moving faster than v_s comes within d̂ of it: predicted at a step's start, it wakes before
/// Newton runs; found at the step's end, it wakes and the step is solved again (Simulation), so no
/// accepted step has a moving body meet a held one. A woken body rests t_s again before it sleeps
/// again. Bodies joined by joints sleep and wake together, and a joint counts as touching. A step
/// in which every dynamic body sleeps does no Newton iteration. What it trades
/// (docs/sleeping.md): a sleeping body no longer creeps (friction's slip below ε_v, a pile settling
/// slower than v_s), nor moves under a body slower than v_s.

#include <Eigen/Core>
#include <vector>

#include <stiffsoft/coupling/contact/constraint_set.hpp>

namespace stiffsoft {

struct Model;

/// Which bodies sleep, and for how long each awake one has been at rest.
class Sleeping {
 public:
  /// What a Simulation carries from step to step (and a checkpoint keeps), per body of the model.
  struct State {
    Eigen::VectorXd rest_time;  ///< seconds it has rested (touching, below v_s); kept while it sleeps
    Eigen::VectorXd asleep;     ///< 1 while it sleeps, −1 awake (every value ≥ 0 reads as asleep)
  };

  /// Nobody asleep. `time` t_s (s) > 0, `speed` v_s (m/s) > 0.
  Sleeping(const Model& model, double time, double speed);

  /// The state now.
  const State& state() const { return m_state; }
  /// Continues from `s`; empty vectors (a state saved without sleeping) wake every body and
  /// restart their rest times; std::invalid_argument when they have neither no entry nor one per
  /// body. Session 64 wrote sleeping islands' labels (≥ 0) there in format 3: they read as asleep.
  void restore(const State& s);

  /// Whether body b sleeps.
  bool asleep(int b) const { return m_state.asleep[b] >= 0; }
  /// Number of sleeping bodies.
  int sleeping_count() const;
  /// Whether every dynamic affine body sleeps and no DOF is left to move (no soft node, no
  /// kinematic body): a step has nothing to solve.
  bool all_asleep() const;
  /// Per body, 1 for the bodies that cannot move this step: sleeping and fixed affine bodies
  /// (BarrierTerm::hold_still leaves the contacts among them out).
  std::vector<char> still_bodies() const;
  /// The DOF blocks of the sleeping bodies, in body order.
  std::vector<int> held_blocks() const;

  /// At a step's start, before Newton: wakes every sleeping body a moving body may reach. A body
  /// moves when it is awake, carries DOFs (a kinematic or soft body too) and some surface point of
  /// it moves faster than v_s from `x_n` to `x_start` (surface positions at qⁿ and at Newton's
  /// start, a step h apart); its box swept between the two, grown by d̂ plus the length of its
  /// largest move (Newton may go further than its start), is checked against each sleeping body's
  /// box at `x_n` grown by d̂. A woken body's rest time starts again from 0. Returns the bodies
  /// woken.
  std::vector<int> wake_near_moves(const Eigen::MatrixX3d& x_n, const Eigen::MatrixX3d& x_start, double dhat,
                                   double h);
  /// At a step's end, before it is accepted: wakes every sleeping body that a body moving faster
  /// than v_s from `x_n` to `x_new` (the step's result) came within d̂ of (their boxes, the
  /// mover's swept from `x_n` to `x_new`, both grown by d̂). Returns the bodies woken; when there
  /// are any, the step is to be solved again with them awake.
  std::vector<int> wake_met_by_moves(const Eigen::MatrixX3d& x_n, const Eigen::MatrixX3d& x_new, double dhat,
                                     double h);

  /// At a step's end: each awake dynamic affine body's rest time grows by h when it touches
  /// something (an active contact of `contacts`, or a joint) and no surface point moves faster
  /// than v_s (`surface_velocity`, |V|×3), else it restarts from 0; soft bodies never rest. Then
  /// every body whose rest time has reached t_s sleeps if each dynamic body it touches (by a
  /// contact or a joint) sleeps or has rested t_s too (so that a body still moving keeps its
  /// neighbours awake, and sleeping bodies meet moving ones only across an awake one), and so can
  /// every body of its joint group. Returns the bodies that fell asleep in this call.
  std::vector<int> end_step(const std::vector<ContactConstraint>& contacts,
                            const Eigen::MatrixX3d& surface_velocity, double h);

 private:
  /// Wakes the sleeping bodies that the boxes of the moves from `x_n` to `x_to` faster than v_s,
  /// grown by d̂ (and, with `grow_by_move`, by the move's length), meet, with their joint
  /// groups; see wake_near_moves.
  std::vector<int> wake_reached(const Eigen::MatrixX3d& x_n, const Eigen::MatrixX3d& x_to, double dhat,
                                double h, bool grow_by_move);

  const Model& m_model;
  double m_time, m_speed;
  State m_state;
  /// Per body, its joint group: the lowest index of the bodies carrying DOFs that joints join it
  /// to, directly or along a chain (itself when none). A joint's eliminated equalities tie its
  /// bodies' DOFs, so a group is held, or moves, whole.
  std::vector<int> m_group;
  /// Per body, whether some joint ends on it (to another body, a fixed one or the world).
  std::vector<char> m_jointed;
};

}  // namespace stiffsoft
