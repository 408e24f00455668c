#include "peers/csv.hpp"

#include <cmath>
#include <iomanip>

namespace stiffsoft::peers {

namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

void write_csv_header(std::ostream& out, const Machine& machine, int threads) {
  out << "# machine: " << machine.cores << " cores (std::thread::hardware_concurrency), cpu: " << machine.cpu << "\n"
      << "# date: " << machine.date << "\n"
      << "# threads: stiffsoft " << threads << " (TBB), Bullet 1, MuJoCo 1\n"
      << "engine,scene,bodies,dynamic_bodies,triangles,dt,steps,duration_s,ms_median,ms_mean,wall_s,newton_mean,"
         "unconverged,broad_phase_ms,ccd_ms,assembly_ms,solve_ms,smallest_distance_m,frames_checked,"
         "frames_intersecting,max_overlap_m,max_overlap_where,max_engine_depth_m,engine_depth_where,"
         "tunnelling_events,tunnelled,tunnel_note,first_intersection,warnings,statistics,threads,load_before,"
         "load_after,settings\n";
}

void write_csv_row(std::ostream& out, const RunResult& r) {
  const AccuracyReport& a = r.accuracy;
  out << std::setprecision(9) << r.engine << ',' << r.scene << ',' << r.bodies << ',' << r.dynamic_bodies << ','
      << r.triangles << ',' << r.dt << ',' << r.steps << ',' << r.duration << ',' << r.ms_median << ',' << r.ms_mean
      << ',' << r.wall_s << ',' << r.newton_mean << ',' << r.unconverged << ',' << r.broad_phase_ms << ',' << r.ccd_ms
      << ',' << r.assembly_ms << ',' << r.solve_ms << ',';
  if (std::isfinite(a.smallest_distance)) out << a.smallest_distance;
  out << ',' << a.frames_checked << ',' << a.frames_intersecting << ',' << a.max_overlap << ','
      << quoted(a.max_overlap_where) << ',' << a.max_engine_depth << ',' << quoted(a.engine_depth_where) << ','
      << a.tunnelling_events << ',' << (a.tunnelled ? 1 : 0) << ',' << quoted(a.tunnel_note) << ','
      << quoted(a.first_intersection) << ',' << quoted(r.warnings) << ',' << quoted(r.statistics) << ',' << r.threads
      << ',' << r.load_before << ',' << r.load_after << ',' << quoted(r.settings) << '\n';
  out.flush();
}

}  // namespace stiffsoft::peers
