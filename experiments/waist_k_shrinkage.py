"""Decision W48: the calibrated pendulum gain K shrunk toward the population K0 by precision weighting.

A calibration walk of known length gives ``K_cal`` (seed 003 eq. 1 with F = 0, the fit of decision W8) and, from
its own per-stride scatter, a standard error: per stride j (two consecutive steps) the implied gain under a
constant step length over the walk, ``K_j = (D / sum c - F) (c_a + c_b) / (c_a g_a + c_b g_b)``, and
``se = sd(K_j) / sqrt(n_strides)`` (stride, not step, is the unit: W40). The prior is mobgap's population factor
``K0 = 4.587 / 4`` (W46) with between-subject spread ``tau``; the shrunk gain is the precision-weighted mean
``K = (K_cal / se^2 + K0 / tau^2) / (1 / se^2 + 1 / tau^2)`` (the normal-normal posterior mean, e.g. Gelman et
al., Bayesian Data Analysis, 3rd ed., eq. 2.12 / sec. 5.4).

tau is never fitted on the tested subject: for each held-out subject it is the method-of-moments estimate from the
other two subjects' Test5 calibration walks (each subject: K_cal and se over all its referenced Test5 trials),
``tau^2 = mean((K_cal,s - K0)^2) - mean(se_s^2)`` -- about K0, not about the subjects' own mean, because the prior's
mean is fixed (mobgap's value, W46) and what the shrinkage acts on is the distance from it -- floored at
``mean(se_s^2)`` so that a walk as long as the evidence's own keeps at least half its weight (two or three subjects
can give a moment estimate <= 0 by chance; the floor keeps a calibration from being discarded). The textbook
sample-variance form (var(K_cal,s) - mean se_s^2) is printed beside it for information only. The simulator's users
are calibrated with tau from all three mobgap subjects (the shipped value); their own K_cal / se and the tau they
would give are printed. F stays as calibrated: the prior is a prior on K of the F = 0 model (mobgap's SlZijlstra
has no offset), so K is shrunk only when the fit is K only with F = 0 (walks of one speed, W8); a joint K/F fit
(walks of different speeds) is left alone.

Adoption rule (fixed before measuring, as the task states it): adopt shrinkage as the default of `calibrate` only
if (1) the held-out Test5 pooled median |bout error| vs `Length` falls below 4.033 % (the calibrated value of W40),
(2) no subject is worse by more than 0.5 points (per subject: the median |bout error| over its held-out Test5
bouts; HA001 and MS001, two each -- HA002 has one referenced Test5 trial and no Test5 test), (3) the pooled
Test11 medians vs `Length` (25.415 %) and vs the bouts' strides (8.350 %) are not higher, and (4) the simulator's
`waist-pendulum` median |distance error| (1.870 %) is not higher (each as printed at 3 decimals).

Run: .venv/bin/python experiments/waist_k_shrinkage.py [--external datasets/external] [--sim-users 3]
Writes experiments/results/waist_k_shrinkage.md.
"""
