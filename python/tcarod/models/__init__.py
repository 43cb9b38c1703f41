"""Models built on the API over the core (nothing here is imported by the API):

* :mod:`~tcarod.models.manipulators` -- the paper's manipulators and finger, material presets, turns readings;
* :mod:`~tcarod.models.grasp` -- grasping by incremental blocked-tip solves (eq 44);
* :mod:`~tcarod.models.thermal` -- voltage to temperature (lumped electro-thermal model);
* :mod:`~tcarod.models.trajectory` -- robots driven by voltages, quasi-static shape trajectories;
* :mod:`~tcarod.models.segmented` -- actuators made of TCA segments in series;
* :mod:`~tcarod.models.workspace` -- workspace maps over temperature grids;
* :mod:`~tcarod.models.calibration` -- fitting material parameters to measured TCA curves;
* :mod:`~tcarod.models.identification` -- identifying the Table I contact and rho scale;
* :mod:`~tcarod.models.studies` -- sensitivity studies;
* :mod:`~tcarod.models.bruteforce` -- brute-force references for the inverse methods;
* :mod:`~tcarod.models.stability` -- stability verdicts and branch following.
"""
