# Layer: elements. Modules and the objects of the modules each one uses.
MODULES += cfe_element continuum_element distributed_loads element_interface element_library materials shape_functions \
           material_laws nonlinear_continuum spring_element truss_element deformation_plasticity heat_element element_mass
$(OBJDIR)/cfe_element.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/element_interface.o $(OBJDIR)/kinds.o $(OBJDIR)/shape_functions.o
$(OBJDIR)/continuum_element.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/element_interface.o $(OBJDIR)/kinds.o $(OBJDIR)/materials.o $(OBJDIR)/shape_functions.o
$(OBJDIR)/distributed_loads.o: $(OBJDIR)/continuum_element.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/shape_functions.o
$(OBJDIR)/element_interface.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o
$(OBJDIR)/element_library.o: $(OBJDIR)/continuum_element.o $(OBJDIR)/element_interface.o \
                             $(OBJDIR)/nonlinear_continuum.o $(OBJDIR)/spring_element.o $(OBJDIR)/truss_element.o
$(OBJDIR)/deformation_plasticity.o: $(OBJDIR)/kinds.o
$(OBJDIR)/material_laws.o: $(OBJDIR)/deformation_plasticity.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/element_interface.o $(OBJDIR)/kinds.o \
                           $(OBJDIR)/materials.o $(OBJDIR)/model.o $(OBJDIR)/small_matrices.o
$(OBJDIR)/nonlinear_continuum.o: $(OBJDIR)/continuum_element.o $(OBJDIR)/element_catalogue.o \
                                 $(OBJDIR)/element_interface.o $(OBJDIR)/kinds.o $(OBJDIR)/material_laws.o \
                                 $(OBJDIR)/model.o $(OBJDIR)/shape_functions.o $(OBJDIR)/small_matrices.o
$(OBJDIR)/materials.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/small_matrices.o
$(OBJDIR)/shape_functions.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o
$(OBJDIR)/spring_element.o: $(OBJDIR)/element_interface.o $(OBJDIR)/kinds.o
$(OBJDIR)/truss_element.o: $(OBJDIR)/element_interface.o $(OBJDIR)/kinds.o $(OBJDIR)/shape_functions.o
$(OBJDIR)/heat_element.o: $(OBJDIR)/continuum_element.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/shape_functions.o
$(OBJDIR)/element_mass.o: $(OBJDIR)/continuum_element.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/shape_functions.o
