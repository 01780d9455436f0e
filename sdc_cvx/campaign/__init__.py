"""Removal campaigns: K missions over several years, with a certified campaign bound.

- :mod:`~sdc_cvx.campaign.pricing`: one launch's missions under prices on the debris
  (the certified single-mission search with node costs), returned as columns;
- :mod:`~sdc_cvx.campaign.master`: the set-packing master over those columns, declared
  in CVXPY (its LP gives prices, its integer program a plan);
- :mod:`~sdc_cvx.campaign.search`: :func:`solve_campaign`, the entry point: options,
  where the pricing runs, and the objective's search;
- :mod:`~sdc_cvx.campaign.min_dv`: the min-ΔV column generation with the Lagrangian
  bound, the greedy baseline (:mod:`~sdc_cvx.campaign.greedy`) and the closing
  enumeration;
- :mod:`~sdc_cvx.campaign.value`, :mod:`~sdc_cvx.campaign.value_bound`,
  :mod:`~sdc_cvx.campaign.value_start`: the most valuable campaign, its bound and a
  first campaign of high value;
- :mod:`~sdc_cvx.campaign.result`: :class:`CampaignSolution`.

See ``docs/design.md`` §10.
"""
