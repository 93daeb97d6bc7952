"""The paper's loop, as a START sends it (firmware/include/tvo/defaults.h writes the values once; read
from it at build time into _defaults_h.py): what tvo_controller_config_default gives and tvo_sim sends.

    from tvo import defaults
    s.gain_kp, s.gain_kd = defaults.GAIN_KP, defaults.GAIN_KD     # 40.0, 13.0
"""
from ._defaults_h import (ACCEL_MAX_MPS2, DELAY_US, FILTER_TF_S, GAIN_KD, GAIN_KP, MIN_SPEED_MPS, OMEGA_MAX_RADPS,
                          PERIOD_US, SPEED_MAX_MPS, WATCHDOG_PERIODS)

__all__ = ["PERIOD_US", "DELAY_US", "WATCHDOG_PERIODS", "FILTER_TF_S", "GAIN_KP", "GAIN_KD", "OMEGA_MAX_RADPS",
           "ACCEL_MAX_MPS2", "SPEED_MAX_MPS", "MIN_SPEED_MPS"]
