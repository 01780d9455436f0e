"""Removal campaigns: K missions over several years, with a certified campaign bound.

- :mod:`~sdc_cvx.campaign.pricing`: one launch's missions under prices on the debris
  (the certified single-mission search with node costs), returned as columns;
- :mod:`~sdc_cvx.campaign.master`: the set-packing master over those columns, declared
  in CVXPY (its LP gives prices, its integer program a plan);
- :mod:`~sdc_cvx.campaign.search`: :func:`solve_campaign`, the column generation with
  the Lagrangian bound, the greedy baseline and the closing enumeration;
- :mod:`~sdc_cvx.campaign.result`: :class:`CampaignSolution`.

See ``docs/design.md`` §10.
"""
