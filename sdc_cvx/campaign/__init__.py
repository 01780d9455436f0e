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
  :mod:`~sdc_cvx.campaign.value_start`, :mod:`~sdc_cvx.campaign.value_pool`: the most
  valuable campaign, its bound, a first campaign of high value, and the programs over a
  pool of priced missions (most value, value at a price, the value-ΔV front);
- :mod:`~sdc_cvx.campaign.few`: missions of one debris or none (value objectives);
- :mod:`~sdc_cvx.campaign.result`: :class:`CampaignSolution`.

See ``docs/design.md`` §10.
"""
