#!/usr/bin/env python3
"""OpenSim's inverse dynamics tool on a model and a motion, for tests/inverse_opensim.rs (OpenSim 4.6 from
PyPI: scripts/opensim-venv.sh).

  opensim_id.py [--keep-forces] MODEL.osim MOTION.mot OUT_DIR CUTOFF_HZ [EXTERNAL_LOADS.xml]

runs InverseDynamicsTool over the whole motion (forces other than gravity excluded, unless --keep-forces:
then the model's forces, e.g. its SpringGeneralizedForces, act and the tool subtracts them; CUTOFF_HZ -1
leaves the coordinates unfiltered, as the tool's lowpass_cutoff_frequency does), with the ExternalLoads
file if given, and writes OUT_DIR/opensim_id.sto.
"""
import os
import sys

import opensim as osim

osim.Logger.setLevelString("error")
osim.Logger.removeFileSink()  # no opensim.log left behind


def main():
    keep_forces = "--keep-forces" in sys.argv
    args = [a for a in sys.argv[1:] if a != "--keep-forces"]
    model, motion, out_dir, cutoff = args[0], args[1], args[2], float(args[3])
    storage = osim.Storage(motion)
    tool = osim.InverseDynamicsTool()
    tool.setModelFileName(os.path.abspath(model))
    tool.setCoordinatesFileName(os.path.abspath(motion))
    tool.setLowpassCutoffFrequency(cutoff)
    tool.setStartTime(storage.getFirstTime())
    tool.setEndTime(storage.getLastTime())
    excluded = osim.ArrayStr()
    if not keep_forces:
        excluded.append("All")
    tool.setExcludedForces(excluded)
    if len(args) > 4:
        tool.setExternalLoadsFileName(os.path.abspath(args[4]))
    tool.setResultsDir(os.path.abspath(out_dir))
    tool.setOutputGenForceFileName("opensim_id.sto")
    if not tool.run():
        sys.exit("InverseDynamicsTool failed")


if __name__ == "__main__":
    main()
