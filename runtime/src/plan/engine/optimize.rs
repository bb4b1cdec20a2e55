//! The backward pass over the look-ahead window (`tpRunOptimization`).

use super::{pair_mut, Planner, Term, MIN_SEGMENT_CYCLES};

impl Planner {
    /// `tpRunOptimization`: backward pass from the newest element over at most
    /// `depth` junctions, stopping at the second junction that is not tangent.
    pub(super) fn optimize(&mut self) {
        let len = self.queue.len();
        let mut hit_non_tangent = false;
        let mut hit_peaks = 0;
        let lazy = self.lcnc();
        for x in 1..self.depth + 2 {
            if x + 1 > len {
                return;
            }
            let ind = len - x;
            let (head, tail) = self.queue.as_mut_slices();
            let (prev, tc) = pair_mut(head, tail, ind - 1, ind);
            if prev.term != Term::Tangent {
                if hit_non_tangent {
                    return;
                }
                hit_non_tangent = true;
                continue;
            }
            if !tc.finalized {
                let vpeak = (tc.tangential_accel() * tc.target).sqrt();
                let mut tv = tc.max_target_vel();
                if !tc.pure_rotary {
                    tv = tv.min(self.p.traj_max_velocity);
                }
                let mut fv = prev.maxvel.min(vpeak.min(tv));
                if prev.kink_vel >= 0.0 {
                    fv = fv.min(prev.kink_vel);
                }
                prev.finalvel = fv;
                tc.finalvel = 0.0;
            } else {
                let a = tc.tangential_accel();
                let vs_back = (tc.finalvel * tc.finalvel + 2.0 * a * tc.target).sqrt();
                let mut limit = tc.maxvel.min(prev.maxvel);
                if prev.kink_vel >= 0.0 {
                    limit = limit.min(prev.kink_vel);
                }
                if vs_back >= limit {
                    prev.at_max = true;
                }
                let fv = vs_back.min(limit);
                let clamp = tc.maxvel.min(tc.target / (self.cycle * MIN_SEGMENT_CYCLES));
                // Once a junction comes out as it was, every earlier one would too
                // (their inputs are unchanged), so the rest of the pass is skipped.
                // The result equals LinuxCNC's full pass; the cost is O(1) amortised
                // on long chains instead of O(depth).
                let unchanged = prev.optimized && fv == prev.finalvel && clamp == tc.maxvel;
                // Past the run's highest target speed both the old and the new
                // value are spent as that speed, and so is every value the rest of
                // the pass would compute from them (the step below never lowers a
                // speed, as acceleration is not negative, and a cap under the run's
                // speed gives both the same value), so the rest of the pass changes
                // nothing that is executed. Only from the third junction on, where
                // every older element's limits are final, and not with LinuxCNC's
                // lazy cut-off, which counts the `at_max` flags this would skip.
                let saturated = !lazy
                    && x >= 3
                    && prev.optimized
                    && clamp == tc.maxvel
                    && fv >= prev.run_vmax
                    && prev.finalvel >= prev.run_vmax;
                prev.finalvel = fv;
                prev.optimized = true;
                tc.maxvel = clamp;
                if unchanged || saturated {
                    return;
                }
            }
            // LinuxCNC's lazy optimisation: stop after passing more than
            // TP_OPTIMIZATION_CUTOFF (4) elements already at their speed limit.
            if lazy && tc.at_max {
                hit_peaks += 1;
                if hit_peaks > 4 {
                    return;
                }
            }
        }
    }
}
