"""carousel-theory: exact variance propagation of MEMS gyro error processes under averaging and
carouseling (Collin, Kirkko-Jaakkola, Takala, IEEE TIM 2014), bias prediction for 1/f gyro noise
(Kirkko-Jaakkola, Collin, Takala, IEEE Sensors J. 2012), and their check against measured data."""

__version__ = "0.1.0"
